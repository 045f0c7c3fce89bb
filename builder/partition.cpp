// partition.cpp: splits a weighted graph into parts of bounded weight by recursive bisection.
// Each bisection of a set of weight w into k = ceil(w / max) parts takes floor(k/2) parts' worth of
// weight for side A by breadth-first growth from the set's extreme node along its longest axis; the
// rest is side B. BFS from an extreme node cuts like a plane sweep that follows the surface, so both
// sides stay compact and A is connected (it jumps to the next extreme node only when its component runs
// out). Because every set is cut in proportion to its part count, all parts end near w / k: a mesh of
// 50k triangles gives parts of ~127.9 triangles, where greedy growing leaves half-empty leftovers.
// The two halves are independent, so the top of the recursion runs on several threads; a part's place
// in the output depends only on the recursion tree, never on which thread ran it.
#include <algorithm>
#include <thread>

#include "builder.h"

namespace vgeo {
namespace {

constexpr uint32_t kTaken = 0x80000000u;

struct Bisector {
  const Graph& graph;
  const std::vector<uint8_t>& weights;
  const std::vector<glm::vec3>& positions;
  uint32_t maxWeight;
  const std::function<bool(const uint32_t*, size_t)>& fits;
  std::vector<uint32_t>& order;
  std::vector<uint32_t> stamp;   // the end of the segment a node lives in; kTaken|end while being taken
  std::vector<uint8_t> partHead; // 1 at the first position of every part

  uint32_t load(uint32_t node) const { return __atomic_load_n(&stamp[node], __ATOMIC_RELAXED); }
  void store(uint32_t node, uint32_t value) { __atomic_store_n(&stamp[node], value, __ATOMIC_RELAXED); }

  void split(uint32_t lo, uint32_t hi, int parallelDepth) {
    uint64_t w = 0;
    for (uint32_t i = lo; i < hi; i++) w += weights[order[i]];
    if (hi - lo == 1 || (w <= maxWeight && (!fits || fits(&order[lo], hi - lo)))) {
      partHead[lo] = 1;
      return;
    }
    uint64_t k = std::max<uint64_t>(2, (w + maxWeight - 1) / maxWeight);
    uint64_t kA = k / 2;
    uint64_t targetA = (w * kA + k / 2) / k;
    uint64_t maxA = w <= maxWeight ? w - 1 : kA * maxWeight;

    glm::vec3 lower(INFINITY), upper(-INFINITY);
    for (uint32_t i = lo; i < hi; i++) {
      lower = glm::min(lower, positions[order[i]]);
      upper = glm::max(upper, positions[order[i]]);
    }
    glm::vec3 extent = upper - lower;
    int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    auto before = [&](uint32_t a, uint32_t b) {
      float pa = positions[a][axis], pb = positions[b][axis];
      return pa != pb ? pa < pb : a < b;
    };

    const uint32_t inSet = hi, taken = hi | kTaken;
    std::vector<uint32_t> sideA;  // in BFS order
    sideA.reserve(size_t(hi - lo) / 2 + 1);
    std::vector<uint32_t> seeds;  // the set sorted along the axis, made only when a component runs out
    size_t nextSeed = 0;
    uint64_t wA = 0;
    size_t head = 0;
    auto take = [&](uint32_t node) {
      store(node, taken);
      sideA.push_back(node);
      wA += weights[node];
    };
    uint32_t seed = order[lo];
    for (uint32_t i = lo + 1; i < hi; i++)
      if (before(order[i], seed)) seed = order[i];
    take(seed);
    while (wA < targetA) {
      if (head == sideA.size()) {
        // Component exhausted: continue from the extreme node not yet taken.
        if (seeds.empty()) {
          seeds.assign(order.begin() + lo, order.begin() + hi);
          std::sort(seeds.begin(), seeds.end(), before);
        }
        while (nextSeed < seeds.size() && load(seeds[nextSeed]) != inSet) nextSeed++;
        if (nextSeed == seeds.size()) break;
        if (wA + weights[seeds[nextSeed]] > maxA) break;
        take(seeds[nextSeed]);
        continue;
      }
      uint32_t node = sideA[head++];
      for (uint32_t e = graph.offsets[node]; e < graph.offsets[node + 1] && wA < targetA; e++) {
        uint32_t next = graph.adjacency[e];
        if (load(next) == inSet && wA + weights[next] <= maxA) take(next);
      }
    }
    if (sideA.size() == hi - lo) {  // never take everything
      store(sideA.back(), inSet);
      sideA.pop_back();
    }
    const uint32_t mid = lo + uint32_t(sideA.size());
    // Rewrite the segment: A in BFS order, then B in its previous order.
    std::vector<uint32_t> sideB;
    sideB.reserve(hi - mid);
    for (uint32_t i = lo; i < hi; i++)
      if (load(order[i]) == inSet) sideB.push_back(order[i]);
    std::copy(sideA.begin(), sideA.end(), order.begin() + lo);
    std::copy(sideB.begin(), sideB.end(), order.begin() + mid);
    for (uint32_t node : sideA) store(node, mid);
    std::vector<uint32_t>().swap(sideA);
    std::vector<uint32_t>().swap(sideB);
    std::vector<uint32_t>().swap(seeds);

    if (parallelDepth > 0) {
      std::thread other([&] { split(lo, mid, parallelDepth - 1); });
      split(mid, hi, parallelDepth - 1);
      other.join();
    } else {
      split(lo, mid, 0);
      split(mid, hi, 0);
    }
  }
};

}  // namespace

Partition partitionGraph(const Graph& graph, const std::vector<uint8_t>& weights, const std::vector<glm::vec3>& positions,
                         uint32_t maxWeight, int threads, const std::function<bool(const uint32_t*, size_t)>& fits) {
  const uint32_t n = uint32_t(graph.nodeCount());
  Partition result;
  if (n == 0) return result;
  result.order.resize(n);
  for (uint32_t i = 0; i < n; i++) result.order[i] = i;
  Bisector b{graph, weights, positions, maxWeight, fits, result.order, std::vector<uint32_t>(n, n), std::vector<uint8_t>(n, 0)};
  int depth = 0;
  while ((1 << depth) < threads) depth++;
  b.split(0, n, depth);
  for (uint32_t i = 1; i < n; i++)
    if (b.partHead[i]) result.partStart.push_back(i);
  result.partStart.push_back(n);
  return result;
}

}  // namespace vgeo
