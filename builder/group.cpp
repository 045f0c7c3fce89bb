// group.cpp: neighbouring clusters into groups for simplification (Nanite's grouping step).
// Two clusters are neighbours when they share an edge; the edge weight is how many edges they share,
// so METIS's partition, which minimises the cut weight, makes groups whose outer border is short.
// That border is what the simplifier must lock, so a short border leaves room to halve the group.
#include <metis.h>

#include <algorithm>

#include "../common/parallel.h"

#include "builder.h"

namespace vgeo {

std::vector<GroupPlan> groupClusters(const std::vector<BuildCluster>& clusters, const std::vector<uint32_t>& active,
                                     uint32_t targetSize, int threads, std::vector<uint64_t>* openEdges) {
  const size_t n = active.size();
  // Border edges of each cluster (edges used once inside it), tagged with the cluster's slot.
  std::vector<std::vector<uint64_t>> clusterBorders(n);
  parallelFor(n, threads, [&](size_t slot) {
    const auto& idx = clusters[active[slot]].indices;
    std::vector<uint64_t> local;
    for (size_t t = 0; t + 2 < idx.size(); t += 3)
      for (int i = 0; i < 3; i++) {
        uint32_t a = idx[t + size_t(i)], b = idx[t + size_t((i + 1) % 3)];
        local.push_back(uint64_t(std::min(a, b)) << 32 | std::max(a, b));
      }
    std::sort(local.begin(), local.end());
    for (size_t i = 0; i < local.size();) {
      size_t j = i;
      while (j < local.size() && local[j] == local[i]) j++;
      if (j - i == 1) clusterBorders[slot].push_back(local[i]);
      i = j;
    }
  });
  std::vector<std::pair<uint64_t, uint32_t>> borders;
  for (size_t slot = 0; slot < n; slot++)
    for (uint64_t e : clusterBorders[slot]) borders.push_back({e, uint32_t(slot)});
  std::vector<std::vector<uint64_t>>().swap(clusterBorders);
  parallelSort(borders, threads);
  // Cluster pairs sharing an edge, counted; an edge on one cluster's border only is open.
  std::vector<uint64_t> pairs;
  if (openEdges) openEdges->clear();
  for (size_t i = 0; i < borders.size();) {
    size_t j = i;
    while (j < borders.size() && borders[j].first == borders[i].first) j++;
    if (j - i == 1 && openEdges) openEdges->push_back(borders[i].first);
    for (size_t a = i; a < j; a++)
      for (size_t b = a + 1; b < j; b++)
        if (borders[a].second != borders[b].second)
          pairs.push_back(uint64_t(std::min(borders[a].second, borders[b].second)) << 32 |
                          std::max(borders[a].second, borders[b].second));
    i = j;
  }
  parallelSort(pairs, threads);
  std::vector<std::vector<std::pair<uint32_t, int>>> neighbours(n);
  for (size_t i = 0; i < pairs.size();) {
    size_t j = i;
    while (j < pairs.size() && pairs[j] == pairs[i]) j++;
    uint32_t a = uint32_t(pairs[i] >> 32), b = uint32_t(pairs[i]);
    neighbours[a].push_back({b, int(j - i)});
    neighbours[b].push_back({a, int(j - i)});
    i = j;
  }

  std::vector<idx_t> part(n, 0);
  idx_t nparts = idx_t((n + targetSize - 1) / targetSize);
  if (nparts > 1) {
    std::vector<idx_t> xadj{0}, adjncy, adjwgt;
    for (size_t i = 0; i < n; i++) {
      for (auto [j, w] : neighbours[i]) {
        adjncy.push_back(idx_t(j));
        adjwgt.push_back(idx_t(w));
      }
      xadj.push_back(idx_t(adjncy.size()));
    }
    idx_t nvtxs = idx_t(n), ncon = 1, objval = 0;
    idx_t options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_SEED] = 1;
    options[METIS_OPTION_NUMBERING] = 0;
    // Recursive bisection rather than k-way: with ~16 clusters a part, k-way cannot coarsen the graph and
    // was 6x slower; recursive bisection also gave shorter borders (armadillo, --subdiv 2).
    int status = METIS_PartGraphRecursive(&nvtxs, &ncon, xadj.data(), adjncy.data(), nullptr, nullptr, adjwgt.data(),
                                          &nparts, nullptr, nullptr, options, &objval, part.data());
    if (status != METIS_OK)
      throw std::runtime_error("METIS_PartGraphRecursive failed with status " + std::to_string(status));
  }
  std::vector<GroupPlan> groups(size_t(std::max<idx_t>(nparts, 1)));
  std::vector<bool> touchesOther(groups.size(), false);
  for (size_t i = 0; i < n; i++) {
    groups[size_t(part[i])].clusters.push_back(active[i]);
    for (auto [j, w] : neighbours[i])
      if (part[j] != part[i]) touchesOther[size_t(part[i])] = true;
  }
  std::vector<GroupPlan> result;
  for (size_t g = 0; g < groups.size(); g++) {
    if (groups[g].clusters.empty()) continue;
    groups[g].isWholeComponent = !touchesOther[g];
    std::sort(groups[g].clusters.begin(), groups[g].clusters.end());
    result.push_back(std::move(groups[g]));
  }
  return result;
}

}  // namespace vgeo
