// group.cpp: neighbouring clusters into groups for simplification (Nanite's grouping step).
// Two clusters are neighbours when they share an edge; the edge weight is how many edges they share,
// so merging the neighbours that share most (group_merge.cpp) makes groups whose outer border is
// short. That border is what the simplifier must lock, so a short border leaves room to halve the
// group.
#include <algorithm>
#include <span>

#include "../common/bucket_sort.h"
#include "../common/parallel.h"

#include "builder.h"

namespace vgeo {

namespace {

// Cluster i's neighbours as (slot, edges shared): neighbourList[neighbourStart[i] .. neighbourStart[i + 1]).
std::span<const std::pair<uint32_t, int>> neighboursOf(const std::vector<uint32_t>& neighbourStart,
                                                       const std::vector<std::pair<uint32_t, int>>& neighbourList,
                                                       size_t i) {
  return {neighbourList.data() + neighbourStart[i], neighbourStart[i + 1] - neighbourStart[i]};
}

// Each of the level's clusters' group (`part`), numbered piece after piece: the whole level, or
// compact pieces of a large one, grouped side by side. Returns the number of groups.
uint32_t partitionIntoGroups(const std::vector<uint32_t>& neighbourStart,
                             const std::vector<std::pair<uint32_t, int>>& neighbourList,
                             const std::vector<BuildCluster>& clusters, const std::vector<uint32_t>& active,
                             const std::vector<glm::vec3>& positions, uint32_t targetSize, int threads,
                             std::vector<uint32_t>& part) {
  const size_t n = active.size();
  auto neighbours = [&](size_t i) { return neighboursOf(neighbourStart, neighbourList, i); };
  FillLaterVector<glm::vec3> centroids(n);
  parallelFor(n, threads, [&](size_t slot) {
    glm::dvec3 sum(0.0);
    const auto& idx = clusters[active[slot]].indices;
    for (uint32_t v : idx) sum += glm::dvec3(positions[v]);
    centroids[slot] = glm::vec3(sum / double(std::max<size_t>(idx.size(), 1)));
  });
  Partition pieces;
  if (n > 2 * size_t(kGroupingPiece)) {
    Graph graph;
    graph.offsets.assign(neighbourStart.begin(), neighbourStart.end());
    graph.adjacency.resize(neighbourList.size());
    parallelForRanges(neighbourList.size(), threads, [&](size_t begin, size_t end) {
      for (size_t k = begin; k < end; k++) graph.adjacency[k] = neighbourList[k].first;
    });
    pieces = partitionGraph(graph, std::vector<uint8_t>(n, 1), centroids, kGroupingPiece + kGroupingPiece / 4,
                            kGroupingPiece, threads);
  } else {
    pieces.order.resize(n);
    for (uint32_t i = 0; i < n; i++) pieces.order[i] = i;
    pieces.partStart.push_back(uint32_t(n));
  }
  std::vector<uint32_t> localOf(n);
  for (size_t p = 0; p < pieces.partCount(); p++)
    for (uint32_t k = pieces.partStart[p]; k < pieces.partStart[p + 1]; k++)
      localOf[pieces.order[k]] = k - pieces.partStart[p];
  // Each piece's groups numbered from 0 in `part`, and how many it has.
  std::vector<uint32_t> pieceGroups(pieces.partCount());
  parallelFor(pieces.partCount(), threads, [&](size_t p) {
    const uint32_t* slots = &pieces.order[pieces.partStart[p]];
    const uint32_t count = pieces.partStart[p + 1] - pieces.partStart[p];
    // The piece's own graph: its clusters and the edges between them.
    WeightedGraph piece;
    std::vector<glm::vec3> pieceCentroids(count);
    for (uint32_t k = 0; k < count; k++) {
      pieceCentroids[k] = centroids[slots[k]];
      for (auto [j, w] : neighbours(slots[k])) {
        const uint32_t at = localOf[j];
        if (at >= count || pieces.order[pieces.partStart[p] + at] != j) continue;  // in another piece
        piece.adjacency.push_back(at);
        piece.weights.push_back(uint32_t(w));
      }
      piece.offsets.push_back(uint32_t(piece.adjacency.size()));
    }
    std::vector<uint32_t> local(count);
    pieceGroups[p] = mergeIntoGroups(piece, pieceCentroids.data(), targetSize, local.data());
    for (uint32_t k = 0; k < count; k++) part[slots[k]] = local[k];
  });
  // Each piece's groups numbered after the earlier pieces'.
  uint32_t groups = 0;
  for (size_t p = 0; p < pieces.partCount(); p++) {
    for (uint32_t k = pieces.partStart[p]; k < pieces.partStart[p + 1]; k++) part[pieces.order[k]] += groups;
    groups += pieceGroups[p];
  }
  return groups;
}

}  // namespace

std::vector<GroupPlan> groupClusters(const std::vector<BuildCluster>& clusters, const std::vector<uint32_t>& active,
                                     const std::vector<glm::vec3>& positions, uint32_t targetSize, int threads,
                                     std::vector<uint64_t>* openEdges, const std::function<void()>& beside) {
  const size_t n = active.size();
  // Border edges of each cluster (edges used once inside it), listed cluster after cluster: entry `at`
  // of cluster `slot` is at borderStart[slot] + its place in the cluster's list.
  std::vector<std::vector<uint64_t>> counted(n);  // of the clusters made without their border
  parallelFor(n, threads, [&](size_t slot) {
    if (clusters[active[slot]].border.empty()) counted[slot] = edgesUsedOnce(clusters[active[slot]].indices);
  });
  auto borderOf = [&](size_t slot) -> const std::vector<uint64_t>& {
    const std::vector<uint64_t>& made = clusters[active[slot]].border;
    return made.empty() ? counted[slot] : made;
  };
  std::vector<uint32_t> borderStart(n + 1, 0);
  for (size_t slot = 0; slot < n; slot++) borderStart[slot + 1] = borderStart[slot] + uint32_t(borderOf(slot).size());
  // The same entries by edge (bucketed by its lower vertex), then cluster: an edge's clusters are a run.
  struct BorderEdge {
    uint64_t edge;
    uint32_t slot, at;
    bool operator<(const BorderEdge& o) const { return edge != o.edge ? edge < o.edge : slot < o.slot; }
  };
  // Up to 4,096 buckets: each chunk (four a thread) counts into a row of them, which with more buckets
  // set the build's peak on many threads; a bucket then sorts tens of entries. A small level takes
  // fewer, about 16 entries a bucket: its rows of counts would otherwise cost more than its entries.
  constexpr int kBorderBucketBits = 12, kEntriesPerBucket = 16;
  const int vertexBits = bitsFor(std::max<size_t>(positions.size(), 1));
  const int bucketBits = std::min({vertexBits, kBorderBucketBits, bitsFor(borderStart[n] / kEntriesPerBucket + 2)});
  FillLaterVector<BorderEdge> borders = bucketSorted<BorderEdge>(
      n, vertexBits, bucketBits, threads,
      [&](size_t slot, auto&& emit) {
        const std::vector<uint64_t>& border = borderOf(slot);
        for (uint32_t k = 0; k < border.size(); k++) {
          const uint64_t edge = border[k];
          emit(edge >> 32, BorderEdge{edge, uint32_t(slot), borderStart[slot] + k});
        }
      },
      std::less<BorderEdge>());
  std::vector<std::vector<uint64_t>>().swap(counted);
  // An edge on one cluster's border only is open: kept a range of the sorted borders at a time, joined
  // in order (the open edges stay ascending). An edge k clusters share gives each of them k - 1
  // neighbour entries, placed where its border entry's are: each cluster's entries follow its border
  // entries' order, so they are counted and placed without a shared counter.
  auto sameEdge = [&](size_t a, size_t b) { return borders[a].edge == borders[b].edge; };
  std::vector<std::vector<uint64_t>> openOf(parallelRangeCount(borders.size()));
  FillLaterVector<uint32_t> entryAt(borderStart[n]);  // the count of each border entry's, then where they go
  parallelForRuns(borders.size(), threads, sameEdge, [&](size_t i, size_t j, size_t range) {
    if (j - i == 1) openOf[range].push_back(borders[i].edge);
    for (size_t a = i; a < j; a++) entryAt[borders[a].at] = uint32_t(j - i - 1);
  });
  if (openEdges) {
    openEdges->clear();
    for (const std::vector<uint64_t>& open : openOf) openEdges->insert(openEdges->end(), open.begin(), open.end());
  }
  std::vector<uint32_t> entries;
  parallelPrefix(
      borderStart[n], threads, [&](size_t k) { return entryAt[k]; }, [&](size_t total) { entries.resize(total); },
      [&](size_t k, size_t at, size_t) { entryAt[k] = uint32_t(at); });
  // A cluster's entries start at its first border entry's (where it has none, at the next cluster's).
  std::vector<uint32_t> entryStart(n + 1, uint32_t(entries.size()));
  for (size_t slot = n; slot-- > 0;)
    entryStart[slot] = borderStart[slot] < borderStart[slot + 1] ? entryAt[borderStart[slot]] : entryStart[slot + 1];
  parallelForRuns(borders.size(), threads, sameEdge, [&](size_t i, size_t j) {
    for (size_t a = i; a < j; a++) {
      uint32_t at = entryAt[borders[a].at];
      for (size_t b = i; b < j; b++)
        if (b != a) entries[at++] = borders[b].slot;
    }
  });
  FillLaterVector<BorderEdge>().swap(borders);
  FillLaterVector<uint32_t>().swap(entryAt);
  // Each cluster's neighbours (slot, edges shared) in ascending order of slot, as a graph: its entries
  // sorted, and a run of equal ones one neighbour (no sort of every pair of the level).
  std::vector<uint32_t> neighbourStart(n + 1, 0);
  parallelFor(n, threads, [&](size_t i) {
    std::sort(entries.begin() + entryStart[i], entries.begin() + entryStart[i + 1]);
    for (uint32_t e = entryStart[i]; e < entryStart[i + 1]; e++)
      neighbourStart[i + 1] += e == entryStart[i] || entries[e] != entries[e - 1];
  });
  for (size_t i = 0; i < n; i++) neighbourStart[i + 1] += neighbourStart[i];
  std::vector<std::pair<uint32_t, int>> neighbourList(neighbourStart[n]);
  parallelFor(n, threads, [&](size_t i) {
    uint32_t at = neighbourStart[i];
    for (uint32_t e = entryStart[i], run = e; e < entryStart[i + 1]; e = run) {
      while (run < entryStart[i + 1] && entries[run] == entries[e]) run++;
      neighbourList[at++] = {entries[e], int(run - e)};
    }
  });
  std::vector<uint32_t>().swap(entries);
  auto neighbours = [&](size_t i) { return neighboursOf(neighbourStart, neighbourList, i); };

  std::vector<uint32_t> part(n, 0);
  uint32_t nparts = 0;
  auto partition = [&] {
    nparts = partitionIntoGroups(neighbourStart, neighbourList, clusters, active, positions, targetSize, threads, part);
  };
  // `beside` runs on the threads that the grouping leaves idle: each piece's merging is one thread's
  // work, and a level has a few pieces at most. The calling thread takes the partition
  // (parallelInvoke's last), so that its arrays come from the malloc arena they came from before.
  if (beside && threads > 1) {
    withThreads(threads, [&] { parallelInvoke(true, beside, partition); });
  } else {
    if (beside) beside();
    partition();
  }
  std::vector<GroupPlan> groups(std::max<uint32_t>(nparts, 1));
  std::vector<bool> touchesOther(groups.size(), false);
  for (size_t i = 0; i < n; i++) {
    groups[part[i]].clusters.push_back(active[i]);
    for (auto [j, w] : neighbours(i))
      if (part[j] != part[i]) touchesOther[part[i]] = true;
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
