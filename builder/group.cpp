// group.cpp: neighbouring clusters into groups for simplification (Nanite's grouping step).
// Two clusters are neighbours when they share an edge; the edge weight is how many edges they share,
// so METIS's partition, which minimises the cut weight, makes groups whose outer border is short.
// That border is what the simplifier must lock, so a short border leaves room to halve the group.
#include <metis.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <span>

#include "../common/bucket_sort.h"
#include "../common/parallel.h"

#include "builder.h"

// METIS draws its random numbers from the C library's rand(), whose one state the whole process
// shares: METIS calls side by side would draw from each other's sequence and partition differently
// on every run. So the builder defines rand and srand itself, over a state for each thread kept by
// the C library's own generator (random_r with the 128-byte state is the sequence glibc's rand gives):
// each METIS call seeds first and then sees the numbers it would see alone, whatever runs beside it.
namespace {
struct ThreadRandom {
  char state[128] = {};
  random_data data = {};
  ThreadRandom() { initstate_r(1, state, sizeof state, &data); }
};
thread_local ThreadRandom threadRandom;

// Each METIS call points SIGABRT and SIGTERM at its own error trap and then puts back the handler it
// found; calls side by side can put back each other's trap, which would outlive them. The handlers
// from before the calls are restored after them.
struct KeptSignalHandlers {
  struct sigaction abortHandler = {}, termHandler = {};
  KeptSignalHandlers() {
    sigaction(SIGABRT, nullptr, &abortHandler);
    sigaction(SIGTERM, nullptr, &termHandler);
  }
  ~KeptSignalHandlers() {
    sigaction(SIGABRT, &abortHandler, nullptr);
    sigaction(SIGTERM, &termHandler, nullptr);
  }
};
}  // namespace

extern "C" void srand(unsigned seed) noexcept { srandom_r(seed, &threadRandom.data); }
extern "C" int rand() noexcept {
  int32_t value = 0;
  random_r(&threadRandom.data, &value);
  return value;
}

namespace vgeo {

namespace {

struct MetisGraph {
  std::vector<idx_t> xadj{0}, adjncy, adjwgt;
  idx_t nodes() const { return idx_t(xadj.size() - 1); }
};

// METIS_PartGraphRecursive on `graph` into `parts` parts of the given shares (equal when null).
void partGraph(const MetisGraph& graph, idx_t parts, real_t* shares, idx_t* part) {
  idx_t nvtxs = graph.nodes(), ncon = 1, objval = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 1;
  options[METIS_OPTION_NUMBERING] = 0;
  // Recursive bisection rather than k-way: with ~16 clusters a part, k-way cannot coarsen the graph
  // and was 6x slower; recursive bisection also gave shorter borders (armadillo, --subdiv 2).
  const int status = METIS_PartGraphRecursive(
      &nvtxs, &ncon, const_cast<idx_t*>(graph.xadj.data()), const_cast<idx_t*>(graph.adjncy.data()), nullptr, nullptr,
      const_cast<idx_t*>(graph.adjwgt.data()), &parts, shares, nullptr, options, &objval, part);
  if (status != METIS_OK)
    throw std::runtime_error("METIS_PartGraphRecursive failed with status " + std::to_string(status));
}

// Parts this few are left to one METIS call; only the cuts above it run side by side.
constexpr idx_t kOneCallParts = 8;

// `parts` parts of `graph` by recursive bisection, as METIS_PartGraphRecursive makes them (each cut
// gives the two sides the shares of the parts they will hold), but with each cut's two sides
// partitioned side by side when `together`: one METIS call over a level of thousands of clusters was
// the serial part of the build. The cuts depend on the graph alone, never on the threads.
void bisectRecursively(const MetisGraph& graph, idx_t parts, idx_t* part, bool together) {
  if (parts <= kOneCallParts) {
    partGraph(graph, parts, nullptr, part);
    return;
  }
  const idx_t n = graph.nodes(), leftParts = parts / 2;
  real_t shares[2] = {real_t(leftParts) / real_t(parts), 0};
  shares[1] = 1 - shares[0];
  std::vector<idx_t> side(size_t(n), 0), at(size_t(n), 0);
  partGraph(graph, 2, shares, side.data());
  MetisGraph halves[2];
  std::vector<idx_t> members[2];
  for (idx_t v = 0; v < n; v++) {
    at[size_t(v)] = idx_t(members[side[size_t(v)]].size());
    members[side[size_t(v)]].push_back(v);
  }
  for (int s = 0; s < 2; s++)
    for (const idx_t v : members[s]) {
      for (idx_t e = graph.xadj[size_t(v)]; e < graph.xadj[size_t(v) + 1]; e++) {
        const idx_t u = graph.adjncy[size_t(e)];
        if (side[size_t(u)] != s) continue;
        halves[s].adjncy.push_back(at[size_t(u)]);
        halves[s].adjwgt.push_back(graph.adjwgt[size_t(e)]);
      }
      halves[s].xadj.push_back(idx_t(halves[s].adjncy.size()));
    }
  std::vector<idx_t> halfPart[2] = {std::vector<idx_t>(members[0].size()), std::vector<idx_t>(members[1].size())};
  auto partitionHalf = [&](int s) {
    if (!members[s].empty())
      bisectRecursively(halves[s], s ? parts - leftParts : leftParts, halfPart[s].data(), together);
  };
  parallelInvoke(
      together, [&] { partitionHalf(0); }, [&] { partitionHalf(1); });
  for (int s = 0; s < 2; s++)
    for (size_t i = 0; i < members[s].size(); i++) part[members[s][i]] = halfPart[s][i] + (s ? leftParts : 0);
}

// Cluster i's neighbours as (slot, edges shared): neighbourList[neighbourStart[i] .. neighbourStart[i + 1]).
std::span<const std::pair<uint32_t, int>> neighboursOf(const std::vector<uint32_t>& neighbourStart,
                                                       const std::vector<std::pair<uint32_t, int>>& neighbourList,
                                                       size_t i) {
  return {neighbourList.data() + neighbourStart[i], neighbourStart[i + 1] - neighbourStart[i]};
}

// Each of the level's clusters' group (`part`), numbered piece after piece: METIS partitions the
// whole level, or compact pieces of a large one, one at a time. Returns the number of groups.
idx_t partitionIntoGroups(const std::vector<uint32_t>& neighbourStart,
                          const std::vector<std::pair<uint32_t, int>>& neighbourList,
                          const std::vector<BuildCluster>& clusters, const std::vector<uint32_t>& active,
                          const std::vector<glm::vec3>& positions, uint32_t targetSize, int threads,
                          std::vector<idx_t>& part) {
  const size_t n = active.size();
  auto neighbours = [&](size_t i) { return neighboursOf(neighbourStart, neighbourList, i); };
  Partition pieces;
  if (n > 2 * size_t(kGroupingPiece)) {
    Graph graph;
    graph.offsets.assign(neighbourStart.begin(), neighbourStart.end());
    graph.adjacency.resize(neighbourList.size());
    parallelForRanges(neighbourList.size(), threads, [&](size_t begin, size_t end) {
      for (size_t k = begin; k < end; k++) graph.adjacency[k] = neighbourList[k].first;
    });
    FillLaterVector<glm::vec3> centroids(n);
    parallelFor(n, threads, [&](size_t slot) {
      glm::dvec3 sum(0.0);
      const auto& idx = clusters[active[slot]].indices;
      for (uint32_t v : idx) sum += glm::dvec3(positions[v]);
      centroids[slot] = glm::vec3(sum / double(std::max<size_t>(idx.size(), 1)));
    });
    pieces = partitionGraph(graph, std::vector<uint8_t>(n, 1), centroids, kGroupingPiece + kGroupingPiece / 4,
                            kGroupingPiece, threads);
  } else {
    pieces.order.resize(n);
    for (uint32_t i = 0; i < n; i++) pieces.order[i] = i;
    pieces.partStart.push_back(uint32_t(n));
  }
  // Each piece's groups are numbered after the earlier pieces'.
  std::vector<idx_t> partBase(pieces.partCount() + 1, 0);
  for (size_t p = 0; p < pieces.partCount(); p++)
    partBase[p + 1] =
        partBase[p] + idx_t((pieces.partStart[p + 1] - pieces.partStart[p] + targetSize - 1) / targetSize);
  std::vector<uint32_t> localOf(n);
  for (size_t p = 0; p < pieces.partCount(); p++)
    for (uint32_t k = pieces.partStart[p]; k < pieces.partStart[p + 1]; k++)
      localOf[pieces.order[k]] = k - pieces.partStart[p];
  const KeptSignalHandlers keptSignalHandlers;
  auto partitionPiece = [&](size_t p) {
    const uint32_t* slots = &pieces.order[pieces.partStart[p]];
    const idx_t count = idx_t(pieces.partStart[p + 1] - pieces.partStart[p]);
    const idx_t pieceParts = partBase[p + 1] - partBase[p];
    std::vector<idx_t> local(size_t(count), 0);
    if (pieceParts > 1) {
      // The piece's own graph: its clusters and the edges between them.
      MetisGraph piece;
      for (idx_t k = 0; k < count; k++) {
        for (auto [j, w] : neighbours(slots[k])) {
          const uint32_t at = localOf[j];
          if (at >= uint32_t(count) || pieces.order[pieces.partStart[p] + at] != j) continue;  // in another piece
          piece.adjncy.push_back(idx_t(at));
          piece.adjwgt.push_back(idx_t(w));
        }
        piece.xadj.push_back(idx_t(piece.adjncy.size()));
      }
      bisectRecursively(piece, pieceParts, local.data(), threads > 1);
    }
    for (idx_t k = 0; k < count; k++) part[slots[k]] = partBase[p] + local[size_t(k)];
  };
  // Inside the arena even for one piece: its bisections' sides run as tasks.
  if (threads > 1)
    withThreads(threads, [&] { parallelFor(pieces.partCount(), threads, partitionPiece); });
  else
    for (size_t p = 0; p < pieces.partCount(); p++) partitionPiece(p);
  return partBase.back();
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

  std::vector<idx_t> part(n, 0);
  idx_t nparts = 0;
  auto partition = [&] {
    nparts = partitionIntoGroups(neighbourStart, neighbourList, clusters, active, positions, targetSize, threads, part);
  };
  // `beside` runs on the threads that the METIS calls leave idle: a cut of thousands of clusters is one
  // thread's work, and the first cuts of a level are a chain. The calling thread takes the partition
  // (parallelInvoke's last), so that its arrays come from the malloc arena they came from before.
  if (beside && threads > 1) {
    withThreads(threads, [&] { parallelInvoke(true, beside, partition); });
  } else {
    if (beside) beside();
    partition();
  }
  std::vector<GroupPlan> groups(size_t(std::max<idx_t>(nparts, 1)));
  std::vector<bool> touchesOther(groups.size(), false);
  for (size_t i = 0; i < n; i++) {
    groups[size_t(part[i])].clusters.push_back(active[i]);
    for (auto [j, w] : neighbours(i))
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
