// chord_rule.h: the chord rule of the DAG build (chord_rule.cpp): which new edges a group's simplification
// may make, so that two groups never make the same edge and no group makes an edge some cluster already
// has (a cut holding both clusters would then hold one edge twice).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "../common/parallel.h"
#include "builder.h"

namespace vgeo {

// Every undirected edge (min << 32 | max) of every cluster made so far, as an open-addressing hash set.
// Threads insert with compare-and-swap (being a set, its contents do not depend on the order). Its
// size is what the batches need, not a power of two: a slot is found by the high half of the hash
// times the size (Lemire's multiply-shift), so that the build's largest array is never twice too big.
class EdgeSet {
 public:
  bool contains(uint64_t key) const;
  // Keeps only the edges for which keep(key) holds and makes room for up to `edges` more, the set at
  // most two thirds full; not thread-safe.
  template <class Keep>
  void retainAndReserve(Keep&& keep, size_t edges, int threads);
  // Whether `edges` more fit with the set at most two thirds full.
  bool hasRoomFor(size_t edges) const { return (count_ + edges) * 3 / 2 + 1 <= capacity_; }
  // Inserts the edges of a cluster's triangles `indices`, given its `border` (edgesUsedOnce of them),
  // thread-safe with itself; false, inserting nothing, when they might not fit.
  bool insertCluster(const std::vector<uint32_t>& indices, const std::vector<uint64_t>& border);

 private:
  static constexpr uint64_t kEmpty = ~uint64_t(0);
  size_t home(uint64_t key) const { return size_t((unsigned __int128)(key * 0x9e3779b97f4a7c15ull) * capacity_ >> 64); }
  size_t next(size_t i) const { return i + 1 == capacity_ ? 0 : i + 1; }
  bool insert(uint64_t key);  // whether the key was new
  std::unique_ptr<uint64_t[]> slots_;
  size_t capacity_ = 0, count_ = 0;
  size_t promised_ = 0, limit_ = 0;  // count_ and the room promised to inserts under way; at most limit_
};

// A new edge between two border vertices of a group (a chord) is made by at most one group of a round,
// and never where some cluster already has that edge. The set of edges made so far grows a round at a
// time, after the round: its chords were checked against earlier rounds only.
class ChordRule {
 public:
  ChordRule(size_t vertices, int threads) : holders_(parallelFilled(vertices * kHolders, UINT32_MAX, threads)) {}
  // Makes room in the set of edges made so far for the edges of clusters [first, end) of `clusters`.
  // When `active` is given (the clusters of the next round), the edges of vertices none of them holds
  // are dropped first: simplification only ever removes vertices, so no later group can ask for those.
  void makeRoom(const std::vector<BuildCluster>& clusters, size_t first, const std::vector<uint32_t>* active,
                int threads);
  // Adds the edges of clusters [first, end) to the set, after makeRoom for them; their `border` must
  // be set. It allocates only when the room made was too little, so that it can run beside other work
  // without raising the peak.
  void addClusters(const std::vector<BuildCluster>& clusters, size_t first, int threads);
  // Records which of this round's groups hold each vertex on a border of their clusters (up to
  // kHolders; a vertex of more groups takes no chord); the clusters' `border` must be set.
  void startRound(const std::vector<GroupPlan>& plans, const std::vector<BuildCluster>& clusters, int threads);
  // Whether group g of this round may make the chord (a, b).
  bool allowed(uint32_t g, uint32_t a, uint32_t b) const;

 private:
  static constexpr uint32_t kHolders = 4;
  EdgeSet edges_;
  FillLaterVector<uint8_t> holderCount_;
  FillLaterVector<uint32_t> holders_;
  uint32_t round_ = 0, roundGroups_ = 0;  // the first id of this round's groups, and how many
};

}  // namespace vgeo
