// topology.cpp: the topology of a triangle soup's surface, from Euler's formula.
// Per connected component (triangles joined through shared edges), V - E + F = 2 - 2g - b for an
// orientable surface of genus g with b boundary loops. The builder uses it to say why a DAG kept several
// roots: a topology-preserving simplifier (the link condition) cannot take a surface of genus g below
// about 4g triangles, nor a boundary loop below three edges, whatever the error allowed.
#include <algorithm>
#include <numeric>

#include "builder.h"
#include "union_find.h"

namespace vgeo {

std::vector<uint64_t> edgesUsedOnce(std::span<const uint32_t> indices) {
  // Counted in an open-addressing table kept by each thread, at most a quarter full (a sort of a
  // cluster's few hundred edges was most of the cost): so sparse that a probe nearly always ends at
  // its first slot, and a corner's edge is counted without a branch on whether it was new. Only the
  // slots taken are emptied again.
  constexpr uint64_t kEmpty = ~uint64_t(0);
  const size_t corners = indices.size() / 3 * 3;
  int bits = 8;
  while ((size_t(1) << bits) < 4 * corners) bits++;
  const size_t mask = (size_t(1) << bits) - 1;
  struct Table {
    std::vector<uint64_t> keys;
    std::vector<uint32_t> uses, taken;  // taken: the slots used, in order
  };
  thread_local Table table;
  if (table.keys.size() <= mask) table.keys.assign(mask + 1, kEmpty), table.uses.assign(mask + 1, 0);
  table.taken.resize(corners);
  uint64_t* keys = table.keys.data();
  uint32_t *uses = table.uses.data(), *taken = table.taken.data();
  size_t takenCount = 0;
  for (size_t t = 0; t < corners; t += 3)
    for (size_t k = 0; k < 3; k++) {
      const uint32_t a = indices[t + k], b = indices[t + (k + 1) % 3];
      const uint64_t key = undirectedEdge(a, b);
      size_t i = size_t((key * 0x9e3779b97f4a7c15ull) >> (64 - bits));
      while (keys[i] != kEmpty && keys[i] != key) i = (i + 1) & mask;
      const bool fresh = keys[i] == kEmpty;
      keys[i] = key;
      uses[i]++;
      taken[takenCount] = uint32_t(i);
      takenCount += fresh;
    }
  std::vector<uint64_t> once;
  for (size_t j = 0; j < takenCount; j++) {
    const uint32_t i = taken[j];
    if (uses[i] == 1) once.push_back(keys[i]);
    keys[i] = kEmpty;
    uses[i] = 0;
  }
  std::sort(once.begin(), once.end());
  return once;
}

std::vector<uint64_t> edgesUsedOnceDense(std::span<const uint32_t> indices, uint32_t vertices) {
  // A counting sort of the edges by their lower vertex; each bucket holds the few upper vertices of
  // one vertex's edges, sorted in place and counted by a scan.
  const size_t corners = indices.size() / 3 * 3;
  std::vector<uint32_t> start(size_t(vertices) + 1, 0), upper(corners);
  auto forEachEdge = [&](auto&& fn) {
    for (size_t t = 0; t < corners; t += 3)
      for (size_t k = 0; k < 3; k++) {
        const uint32_t a = indices[t + k], b = indices[t + (k + 1) % 3];
        fn(std::min(a, b), std::max(a, b));
      }
  };
  forEachEdge([&](uint32_t lower, uint32_t) { start[lower + 1]++; });
  for (uint32_t v = 0; v < vertices; v++) start[v + 1] += start[v];
  std::vector<uint32_t> cursor(start.begin(), start.end() - 1);
  forEachEdge([&](uint32_t lower, uint32_t higher) { upper[cursor[lower]++] = higher; });
  std::vector<uint64_t> once;
  for (uint32_t v = 0; v < vertices; v++) {
    uint32_t* first = upper.data() + start[v];
    uint32_t* last = upper.data() + start[v + 1];
    if (last - first > 16)  // a fan's apex: its edges to the whole fan
      std::sort(first, last);
    else  // insertion sort: a bucket holds a handful
      for (uint32_t* i = first + 1; i < last; i++)
        for (uint32_t* j = i; j > first && j[-1] > j[0]; j--) std::swap(j[-1], j[0]);
    for (uint32_t* i = first; i < last;) {
      uint32_t* run = i + 1;
      while (run < last && *run == *i) run++;
      if (run - i == 1) once.push_back(uint64_t(v) << 32 | *i);
      i = run;
    }
  }
  return once;
}

SurfaceTopology surfaceTopology(const std::vector<uint32_t>& indices) {
  SurfaceTopology t;
  t.triangles = indices.size() / 3;
  // Dense vertex ids.
  std::vector<uint32_t> vertices(indices);
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  auto id = [&](uint32_t v) {
    return uint32_t(std::lower_bound(vertices.begin(), vertices.end(), v) - vertices.begin());
  };
  UnionFind components(vertices.size());
  std::vector<uint64_t> edges;
  edges.reserve(indices.size());
  for (size_t i = 0; i + 2 < indices.size(); i += 3)
    for (int k = 0; k < 3; k++) {
      uint32_t a = id(indices[i + size_t(k)]), b = id(indices[i + size_t((k + 1) % 3)]);
      edges.push_back(undirectedEdge(a, b));
      components.unite(a, b);
    }
  std::sort(edges.begin(), edges.end());
  // Boundary edges (one triangle) joined into loops by their shared vertices.
  UnionFind loops(vertices.size());
  std::vector<uint8_t> onBoundary(vertices.size(), 0);
  size_t uniqueEdges = 0;
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) j++;
    uniqueEdges++;
    if (j - i == 1) {
      uint32_t a = uint32_t(edges[i] >> 32), b = uint32_t(edges[i]);
      onBoundary[a] = onBoundary[b] = 1;
      loops.unite(a, b);
    }
    i = j;
  }
  for (uint32_t v = 0; v < vertices.size(); v++) {
    if (components.find(v) == v) t.components++;
    if (onBoundary[v] && loops.find(v) == v) t.boundaryLoops++;
  }
  // Sum over components of (2 - b_i - chi_i) / 2 = (2 C - b - chi) / 2.
  const int64_t chi = int64_t(vertices.size()) - int64_t(uniqueEdges) + int64_t(t.triangles);
  t.genus = uint64_t(std::max<int64_t>(0, (2 * int64_t(t.components) - int64_t(t.boundaryLoops) - chi) / 2));
  return t;
}

}  // namespace vgeo
