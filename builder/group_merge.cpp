// group_merge.cpp: a graph's nodes into groups of about `target` nodes with short borders,
// by agglomerative merging (Kurita, "An efficient agglomerative clustering algorithm using a heap",
// 1991; the scheme of meshoptimizer's partitionClusters). Each node starts as a group of its own.
// The smallest group (fewest nodes, then lowest id) takes the neighbouring group whose merge scores
// best: the weight of the edges between them (the edges two clusters share, which the merge takes
// off the groups' borders) over the square root of the nodes the two would hold together, so that a
// small neighbour is taken before a large one that shares as much. A group is done when it holds
// `target` nodes, or when no neighbour fits beside it within target + target / 3. Groups merge only
// with neighbours, so each one is connected, except that groups of whole components are put together
// by position at the end. One thread, and the same groups on any machine: ties go to the lower id.
#include <algorithm>
#include <cmath>

#include "builder.h"

namespace vgeo {

uint32_t mergeIntoGroups(const WeightedGraph& graph, const glm::vec3* centroids, uint32_t target, uint32_t* group) {
  const size_t n = graph.nodeCount();
  const uint32_t most = target + target / 3;
  // Each group is named by the node it grew from: its members are linked through nextMember from
  // there, and its size is kept there.
  std::vector<uint32_t> groupOf(n), nextMember(n, UINT32_MAX), lastMember(n), size(n, 1);
  std::vector<uint8_t> done(n, 0);
  for (uint32_t v = 0; v < n; v++) groupOf[v] = lastMember[v] = v;
  // The groups waiting to grow, smallest first; an entry whose size is no longer its group's is stale.
  std::vector<uint64_t> waiting(n);  // size << 32 | group
  for (uint32_t v = 0; v < n; v++) waiting[v] = uint64_t(1) << 32 | v;
  std::make_heap(waiting.begin(), waiting.end(), std::greater<uint64_t>());
  std::vector<uint64_t> shared(n, 0);  // edge weight from the group at hand to each group, while it looks
  std::vector<uint32_t> touched;
  // Group `from` into group `into`: its members relabelled and appended to into's list.
  auto join = [&](uint32_t into, uint32_t from) {
    for (uint32_t v = from; v != UINT32_MAX; v = nextMember[v]) groupOf[v] = into;
    nextMember[lastMember[into]] = from;
    lastMember[into] = lastMember[from];
    size[into] += size[from];
  };
  while (!waiting.empty()) {
    std::pop_heap(waiting.begin(), waiting.end(), std::greater<uint64_t>());
    const uint32_t g = uint32_t(waiting.back()), entrySize = uint32_t(waiting.back() >> 32);
    waiting.pop_back();
    if (groupOf[g] != g || done[g] || entrySize != size[g]) continue;
    if (size[g] >= target) {
      done[g] = 1;
      continue;
    }
    touched.clear();
    for (uint32_t v = g; v != UINT32_MAX; v = nextMember[v])
      for (uint32_t e = graph.offsets[v]; e < graph.offsets[v + 1]; e++) {
        const uint32_t other = groupOf[graph.adjacency[e]];
        if (other == g) continue;
        if (shared[other] == 0) touched.push_back(other);
        shared[other] += graph.weights[e];
      }
    uint32_t best = UINT32_MAX;
    double bestScore = 0.0;
    for (const uint32_t other : touched) {
      const double score = double(shared[other]) / std::sqrt(double(size[g] + size[other]));
      shared[other] = 0;
      if (done[other] || size[g] + size[other] > most) continue;
      if (score > bestScore || (score == bestScore && other < best)) best = other, bestScore = score;
    }
    if (best == UINT32_MAX) {
      done[g] = 1;  // no neighbour fits: it stays as it is
      continue;
    }
    join(g, best);
    waiting.push_back(uint64_t(size[g]) << 32 | g);
    std::push_heap(waiting.begin(), waiting.end(), std::greater<uint64_t>());
  }
  // Groups of whole components (no edge to another group) still short of `target`, as the loose
  // parts of an assembly or the triangles of a soup are, are put together by position: in the order
  // of their centres along a Morton curve, each takes the next while both fit. A group of several
  // such components is then not connected, but it simplifies together, as the groups of one
  // component do, instead of each piece halving alone down to a root of its own.
  std::vector<uint32_t> loose;
  for (uint32_t g = 0; g < n; g++) {
    if (groupOf[g] != g || size[g] >= target) continue;
    bool alone = true;
    for (uint32_t v = g; v != UINT32_MAX && alone; v = nextMember[v])
      for (uint32_t e = graph.offsets[v]; e < graph.offsets[v + 1] && alone; e++)
        alone = groupOf[graph.adjacency[e]] == g;
    if (alone) loose.push_back(g);
  }
  if (loose.size() > 1) {
    std::vector<glm::dvec3> centre(loose.size(), glm::dvec3(0.0));
    glm::dvec3 lower(INFINITY), upper(-INFINITY);
    for (size_t i = 0; i < loose.size(); i++) {
      for (uint32_t v = loose[i]; v != UINT32_MAX; v = nextMember[v]) centre[i] += glm::dvec3(centroids[v]);
      centre[i] /= double(size[loose[i]]);
      lower = glm::min(lower, centre[i]);
      upper = glm::max(upper, centre[i]);
    }
    std::vector<std::pair<uint32_t, uint32_t>> curve(loose.size());  // (Morton code, group)
    const glm::dvec3 scale = 1023.0 / glm::max(upper - lower, glm::dvec3(1e-30));
    for (size_t i = 0; i < loose.size(); i++) {
      const glm::uvec3 cell(glm::clamp((centre[i] - lower) * scale, glm::dvec3(0.0), glm::dvec3(1023.0)));
      uint32_t code = 0;
      for (int bit = 9; bit >= 0; bit--)
        for (int axis = 0; axis < 3; axis++) code = code << 1 | (cell[axis] >> bit & 1u);
      curve[i] = {code, loose[i]};
    }
    std::sort(curve.begin(), curve.end());
    uint32_t into = curve[0].second;
    for (size_t i = 1; i < curve.size(); i++) {
      const uint32_t g = curve[i].second;
      if (size[into] >= target || size[into] + size[g] > most) {
        into = g;
        continue;
      }
      join(into, g);
    }
  }
  // The groups numbered in order of their first node.
  uint32_t groups = 0;
  std::vector<uint32_t> number(n, UINT32_MAX);
  for (uint32_t v = 0; v < n; v++) {
    uint32_t& k = number[groupOf[v]];
    if (k == UINT32_MAX) k = groups++;
    group[v] = k;
  }
  return groups;
}

}  // namespace vgeo
