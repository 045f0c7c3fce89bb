// chord_rule.cpp: the edges made so far and the groups holding each vertex in a round (chord_rule.h).
// Nanite locks group borders so that neighbouring groups simplify independently; a border vertex may
// still gain an edge to another border vertex of its group (a chord), which a neighbouring group could
// make too, or which an earlier cluster may already hold. The set of made edges answers the second;
// each vertex's holders this round the first.
#include "chord_rule.h"

#include <algorithm>

#include "../common/parallel.h"

namespace vgeo {

bool EdgeSet::contains(uint64_t key) const {
  if (capacity_ == 0) return false;
  for (size_t i = home(key);; i = next(i)) {
    uint64_t slot = __atomic_load_n(&slots_[i], __ATOMIC_RELAXED);
    if (slot == key) return true;
    if (slot == kEmpty) return false;
  }
}

bool EdgeSet::insert(uint64_t key) {
  // A plain load first: a locked compare-and-swap waits for the cache line and keeps the loads of
  // other keys from overlapping it, and most keys of a cluster are met a second time (both
  // triangles of an inner edge) or lie in slots already taken.
  for (size_t i = home(key);; i = next(i)) {
    uint64_t slot = __atomic_load_n(&slots_[i], __ATOMIC_RELAXED);
    while (slot == kEmpty) {
      if (__atomic_compare_exchange_n(&slots_[i], &slot, key, false, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) return true;
    }
    if (slot == key) return false;
  }
}

bool EdgeSet::insertCluster(const std::vector<uint32_t>& indices, const std::vector<uint64_t>& border) {
  // Up to 3 new edges a triangle are promised first, so that the table never fills: linear probing
  // would not end in a full one.
  const size_t promise = indices.size();
  if (__atomic_add_fetch(&promised_, promise, __ATOMIC_RELAXED) > limit_) {
    __atomic_sub_fetch(&promised_, promise, __ATOMIC_RELAXED);
    return false;
  }
  // An edge of two of the cluster's triangles runs one way in each (a surface is oriented, and the
  // build stops where it folds), so it is the one of its two that runs up (a < b); an edge of one
  // triangle is on the border. That is about 1.6 keys a triangle instead of 3. The keys' home slots
  // are all asked for before the first insert, so that their cache misses overlap.
  thread_local std::vector<uint64_t> keys;
  keys.resize(indices.size() / 3 * 3 + border.size());
  size_t n = 0;
  for (size_t t = 0; t + 2 < indices.size(); t += 3)
    for (size_t k = 0; k < 3; k++) {
      const uint32_t a = indices[t + k], b = indices[t + (k + 1) % 3];
      keys[n] = undirectedEdge(a, b);
      n += a < b;
    }
  std::copy(border.begin(), border.end(), keys.begin() + long(n));
  keys.resize(n + border.size());
  for (const uint64_t key : keys) __builtin_prefetch(&slots_[home(key)]);
  size_t added = 0;  // counted here, added once: one counter shared by every thread's inserts would not scale
  for (const uint64_t key : keys) added += insert(key);
  __atomic_add_fetch(&count_, added, __ATOMIC_RELAXED);
  __atomic_sub_fetch(&promised_, promise - added, __ATOMIC_RELAXED);
  return true;
}

template <class Keep>
void EdgeSet::retainAndReserve(Keep&& keep, size_t edges, int threads) {
  // The edges kept, counted and then copied out a range of slots at a time straight into one array
  // (no list of each range's to grow and join), then the table made again at its new size (the old
  // one freed first: the two are never held at once). Whether a slot is kept is unpredictable, so it
  // is no branch: every slot is written at the range's next place, which only a kept one takes.
  auto kept = [&](size_t i) {
    const uint64_t key = slots_[i];
    return (key != kEmpty) & keep(key == kEmpty ? 0 : key);
  };
  std::vector<size_t> keptStart(parallelRangeCount(capacity_) + 1, 0);
  parallelForRanges(capacity_, threads, [&](size_t begin, size_t end) {
    size_t n = 0;
    for (size_t i = begin; i < end; i++) n += kept(i);
    keptStart[begin / kParallelRange + 1] = n;
  });
  for (size_t r = 1; r < keptStart.size(); r++) keptStart[r] += keptStart[r - 1];
  FillLaterVector<uint64_t> keys(keptStart.back());
  parallelForRanges(capacity_, threads, [&](size_t begin, size_t end) {
    // Past the range's last kept slot nothing is written: the next place is the next range's.
    for (size_t i = begin, n = keptStart[begin / kParallelRange], last = keptStart[begin / kParallelRange + 1];
         i < end && n < last; i++) {
      keys[n] = slots_[i];
      n += kept(i);
    }
  });
  slots_.reset();
  capacity_ = std::max<size_t>((keys.size() + edges) * 3 / 2 + 1, 1024);
  limit_ = capacity_ - capacity_ / 10;
  slots_.reset(new uint64_t[capacity_]);
  parallelForRanges(capacity_, threads,
                    [&](size_t begin, size_t end) { std::fill(&slots_[begin], &slots_[end], kEmpty); });
  parallelForRanges(keys.size(), threads, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; i++) insert(keys[i]);
  });
  count_ = promised_ = keys.size();
}

namespace {

// Triangles of clusters [first, end).
uint64_t triangleCount(const std::vector<BuildCluster>& clusters, size_t first) {
  uint64_t triangles = 0;
  for (size_t i = first; i < clusters.size(); i++) triangles += clusters[i].indices.size() / 3;
  return triangles;
}

}  // namespace

void ChordRule::makeRoom(const std::vector<BuildCluster>& clusters, size_t first, const std::vector<uint32_t>* active,
                         int threads) {
  // Room for about 1.6 edges a new triangle (a surface's 1.5 and the clusters' borders); inserting
  // stops short of a full table when that was too few (a triangle soup has 3), and then the batch,
  // a set's insertion being idempotent, runs again with room for 3 a triangle.
  const size_t room = size_t(triangleCount(clusters, first) * 8 / 5);
  if (active) {
    FillLaterVector<uint8_t> held = parallelFilled(holders_.size() / kHolders, uint8_t(0), threads);
    parallelFor(active->size(), threads, [&](size_t i) {
      for (uint32_t v : clusters[(*active)[i]].indices) __atomic_store_n(&held[v], uint8_t(1), __ATOMIC_RELAXED);
    });
    edges_.retainAndReserve([&](uint64_t key) { return (held[key >> 32] & held[key & 0xffffffffu]) != 0; }, room,
                            threads);
  }
  if (!edges_.hasRoomFor(room)) edges_.retainAndReserve([](uint64_t) { return true; }, room, threads);
}

void ChordRule::addClusters(const std::vector<BuildCluster>& clusters, size_t first, int threads) {
  for (;;) {
    bool full = false;
    parallelFor(clusters.size() - first, threads, [&](size_t i) {
      const BuildCluster& c = clusters[first + i];
      if (!edges_.insertCluster(c.indices, c.border)) __atomic_store_n(&full, true, __ATOMIC_RELAXED);
    });
    if (!full) break;
    edges_.retainAndReserve([](uint64_t) { return true; }, size_t(triangleCount(clusters, first) * 3), threads);
  }
}

void ChordRule::startRound(const std::vector<GroupPlan>& plans, const std::vector<BuildCluster>& clusters,
                           int threads) {
  const size_t vertices = holders_.size() / kHolders;
  holderCount_ = parallelFilled(vertices, uint8_t(0), threads);
  round_ += roundGroups_;  // this round's groups hold ids round_ + g: entries of earlier rounds are below
  roundGroups_ = uint32_t(plans.size());
  parallelFor(plans.size(), threads, [&](size_t g) {
    // Only a vertex on a cluster's border can be locked in a group (a group's border is made of its
    // clusters'), and every group holding a locked vertex has it on a border: a vertex has one fan,
    // and a group holding part of it has an edge of the fan the rest of it holds. So the borders'
    // vertices are the ones recorded. A group's vertex is counted once: a group runs on one thread,
    // so it sees its own earlier entry; one beyond kHolders is not stored, but then the vertex takes
    // no chord anyway.
    const uint32_t id = round_ + uint32_t(g);
    for (uint32_t m : plans[g].clusters)
      for (uint64_t edge : clusters[m].border)
        for (uint32_t v : {uint32_t(edge >> 32), uint32_t(edge)}) {
          uint32_t* held = &holders_[size_t(v) * kHolders];
          bool seen = false;
          for (uint32_t i = 0; i < kHolders && !seen; i++) seen = __atomic_load_n(&held[i], __ATOMIC_RELAXED) == id;
          if (seen) continue;
          uint8_t slot = __atomic_fetch_add(&holderCount_[v], uint8_t(1), __ATOMIC_RELAXED);
          if (slot < kHolders) __atomic_store_n(&held[slot], id, __ATOMIC_RELAXED);
        }
  });
}

bool ChordRule::allowed(uint32_t g, uint32_t a, uint32_t b) const {
  if (edges_.contains(undirectedEdge(a, b))) return false;
  if (holderCount_[a] > kHolders || holderCount_[b] > kHolders) return false;
  // Of the groups holding both ends, only the first may make the chord this round.
  for (uint32_t i = 0; i < holderCount_[a]; i++)
    for (uint32_t j = 0; j < holderCount_[b]; j++)
      if (holders_[size_t(a) * kHolders + i] == holders_[size_t(b) * kHolders + j] &&
          holders_[size_t(a) * kHolders + i] < round_ + g)
        return false;
  return true;
}

}  // namespace vgeo
