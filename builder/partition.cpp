// partition.cpp: splits a weighted graph into parts of bounded weight by recursive bisection.
// Each bisection of a set of weight w into k = ceil(w / target) parts takes floor(k/2) parts' worth of
// weight for side A, grown from the set's extreme node along its longest axis in order of distance
// from it (so A is a ball around that node, cut from the set by a sphere, which on a large set is
// close to a plane across it); the rest is side B. A is connected: it jumps to the next extreme node
// only when its component runs out. Because every set is cut in proportion to its part count, all
// parts end near w / k, where greedy growing leaves half-empty leftovers. The cuts can still leave a
// part in pieces; a last pass moves each cut-off piece into the neighbour it shares most edges with.
// The two halves are independent, so they run as tasks of their own down to sets of kParallelNodes;
// a part's place in the output depends only on the recursion tree, never on which thread ran it.
// A set of up to kLocalNodes nodes is copied out with the edges inside it and split on the copy: the
// recursion below it then works in cache instead of gathering from arrays over the whole graph.
#include <algorithm>
#include <cstring>
#include <functional>
#include <span>

#include "../common/parallel.h"
#include "builder.h"

namespace vgeo {
namespace {

constexpr uint32_t kTaken = 0x80000000u;
constexpr uint64_t kMedianSplitParts = 64;   // sets of more parts are cut at the weighted median
constexpr uint32_t kParallelNodes = 4096;    // smaller sets are not worth a task of their own
constexpr uint32_t kParallelSet = 1u << 16;  // larger sets' passes run on the threads too
constexpr uint32_t kLocalNodes = 16384;      // a set this small is copied out and split in cache
constexpr uint32_t kScannedSeeds = 4;        // a growth's first new seeds are found by a scan, then by a sort

// Weight and bounds of a set of nodes, and on each axis its first node (least position, then id).
struct SetExtent {
  uint64_t weight = 0;
  glm::vec3 lower{INFINITY}, upper{-INFINITY};
  uint32_t first[3] = {UINT32_MAX, UINT32_MAX, UINT32_MAX};
};

// A node waiting to join side A, keyed by (distance, id) packed into one integer (a distance is never
// negative, so its bits order as the float does): the id breaks ties, so the order is total and the
// heap pops the nodes in one order whatever its layout.
struct FrontierItem {
  uint64_t key;
  uint32_t node;
  bool operator>(const FrontierItem& o) const { return key > o.key; }
};

struct Bisector {
  const Graph& graph;
  const std::vector<uint8_t>& weights;
  const FillLaterVector<glm::vec3>& positions;
  uint32_t targetWeight;  // sets are cut into ceil(weight / targetWeight) parts
  const std::function<bool(const uint32_t*, size_t)>& fits;
  FillLaterVector<uint32_t>& order;
  FillLaterVector<uint32_t> stamp;    // the end of the segment a node lives in; kTaken|end while being taken
  FillLaterVector<uint8_t> partHead;  // 1 at the first position of every part
  bool parallel = false;              // halves as tasks (inside withThreads)
  int threads = 1;
  // On a set's copy (splitCopy): the node ids of the whole graph, which break ties as they would there.
  const uint32_t* ids = nullptr;
  // The local id of each node of a set being copied (splitCopy), over the whole graph; empty where the
  // graph is small enough to stay in cache as it is.
  FillLaterVector<uint32_t>* localOf = nullptr;

  // A bisector over all of `graph`'s nodes as one set: `order` made the identity, every stamp the
  // set's end, no part heads yet.
  static Bisector over(const Graph& graph, const std::vector<uint8_t>& weights,
                       const FillLaterVector<glm::vec3>& positions, uint32_t targetWeight,
                       const std::function<bool(const uint32_t*, size_t)>& fits, FillLaterVector<uint32_t>& order,
                       int threads) {
    const uint32_t n = uint32_t(graph.nodeCount());
    order.resize(n);
    parallelForRanges(n, threads, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; i++) order[i] = uint32_t(i);
    });
    return Bisector{graph,
                    weights,
                    positions,
                    targetWeight,
                    fits,
                    order,
                    parallelFilled(n, n, threads),
                    parallelFilled(n, uint8_t(0), threads),
                    threads > 1,
                    threads};
  }

  uint32_t id(uint32_t node) const { return ids ? ids[node] : node; }
  bool fitsNodes(const uint32_t* nodes, size_t count) const {
    if (!ids) return fits(nodes, count);
    thread_local std::vector<uint32_t> named;
    named.resize(count);
    for (size_t i = 0; i < count; i++) named[i] = ids[nodes[i]];
    return fits(named.data(), count);
  }

  // Sets of kParallelSet nodes or more have their passes on the threads too.
  int threadsFor(uint32_t lo, uint32_t hi) const { return parallel && hi - lo >= kParallelSet ? threads : 1; }

  // Whether node a comes before node b along `axis`: by position, then id.
  bool before(int axis, uint32_t a, uint32_t b) const {
    const float pa = positions[a][axis], pb = positions[b][axis];
    return pa != pb ? pa < pb : id(a) < id(b);
  }

  // Keeps `node` as e's first node on `axis` where it comes before the one kept.
  void keepFirst(SetExtent& e, int axis, uint32_t node) const {
    if (e.first[axis] == UINT32_MAX || before(axis, node, e.first[axis])) e.first[axis] = node;
  }

  // The extent of set [lo, hi), in one pass over ranges on the threads; exact (integer sums, minima and
  // maxima, firsts in a total order), so the same on any thread count.
  SetExtent extentOf(uint32_t lo, uint32_t hi) const {
    // A node is first on an axis only where it is at the least position so far: the position is
    // compared with that least one, kept at hand, and the ids only on a tie.
    auto pass = [&](uint32_t begin, uint32_t end, SetExtent& e) {
      for (uint32_t i = begin; i < end; i++) {
        const uint32_t node = order[i];
        const glm::vec3 p = positions[node];
        e.weight += weights[node];
        e.upper = glm::max(e.upper, p);
        for (int axis = 0; axis < 3; axis++) {
          if (p[axis] < e.lower[axis]) {
            e.lower[axis] = p[axis];
            e.first[axis] = node;
          } else if (p[axis] == e.lower[axis] && id(node) < id(e.first[axis])) {
            e.first[axis] = node;
          }
        }
      }
    };
    SetExtent total;
    if (threadsFor(lo, hi) == 1) {
      pass(lo, hi, total);
      return total;
    }
    std::vector<SetExtent> ranges(parallelRangeCount(hi - lo));
    parallelForRanges(hi - lo, threadsFor(lo, hi),
                      [&](size_t begin, size_t end) { pass(lo + begin, lo + end, ranges[begin / kParallelRange]); });
    for (const SetExtent& r : ranges) {  // every range holds nodes: its firsts are set
      total.weight += r.weight;
      total.lower = glm::min(total.lower, r.lower);
      total.upper = glm::max(total.upper, r.upper);
      for (int axis = 0; axis < 3; axis++) keepFirst(total, axis, r.first[axis]);
    }
    return total;
  }

  // Puts the set's `rank` first nodes in `before` order (by position on `axis`, then id) in front, the
  // rest behind, each side in its previous order: a stable partition around the node of that rank,
  // which is found by counting the nodes into slabs across [lower, upper] and selecting inside the slab
  // that holds it. Every pass runs over ranges on the threads; the order left depends only on the set.
  template <class Before>
  void medianCut(uint32_t lo, uint32_t hi, uint32_t rank, int axis, float lower, float upper, Before&& before) {
    constexpr uint32_t kSlabs = 4096;
    const size_t n = hi - lo;
    const int th = threadsFor(lo, hi);
    const float scale = upper > lower ? float(kSlabs) / (upper - lower) : 0.0f;
    // Each node's slab is kept: the slab is monotonic in the position, so only the nodes of the pivot's
    // slab need their position again to be told apart from the pivot.
    FillLaterVector<uint16_t> slab(n);
    std::vector<uint32_t> counts(parallelRangeCount(n) * kSlabs, 0);
    parallelForRanges(n, th, [&](size_t begin, size_t end) {
      uint32_t* count = &counts[begin / kParallelRange * kSlabs];
      for (size_t i = begin; i < end; i++) {
        slab[i] = uint16_t(std::min(kSlabs - 1, uint32_t((positions[order[lo + i]][axis] - lower) * scale)));
        count[slab[i]]++;
      }
    });
    std::vector<size_t> inSlab(kSlabs, 0);
    for (size_t i = 0; i < counts.size(); i++) inSlab[i % kSlabs] += counts[i];
    uint32_t pivotSlab = 0;
    size_t below = 0;
    while (below + inSlab[pivotSlab] <= rank) below += inSlab[pivotSlab++];
    std::vector<uint32_t> candidates;
    parallelNumber(
        n, th, [&](size_t i) { return slab[i] == pivotSlab; }, [&](size_t total) { candidates.resize(total); },
        [&](size_t i, size_t k) { candidates[k] = order[lo + i]; });
    std::nth_element(candidates.begin(), candidates.begin() + long(rank - below), candidates.end(), before);
    const uint32_t pivot = candidates[rank - below];
    FillLaterVector<uint8_t> front(n);
    parallelForRanges(n, th, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; i++)
        front[i] = slab[i] < pivotSlab || (slab[i] == pivotSlab && before(order[lo + i], pivot));
    });
    FillLaterVector<uint32_t> cut(n);
    parallelNumber(
        n, th, [&](size_t i) { return front[i] != 0; }, [](size_t) {},
        [&](size_t i, size_t k) { cut[k] = order[lo + i]; });
    parallelNumber(
        n, th, [&](size_t i) { return front[i] == 0; }, [](size_t) {},
        [&](size_t i, size_t k) { cut[rank + k] = order[lo + i]; });
    parallelForRanges(n, th, [&](size_t begin, size_t end) {
      std::copy(cut.begin() + long(begin), cut.begin() + long(end), order.begin() + lo + long(begin));
    });
  }

  uint32_t load(uint32_t node) const { return __atomic_load_n(&stamp[node], __ATOMIC_RELAXED); }
  void store(uint32_t node, uint32_t value) { __atomic_store_n(&stamp[node], value, __ATOMIC_RELAXED); }

  void split(uint32_t lo, uint32_t hi) {
    const SetExtent set = extentOf(lo, hi);
    const uint64_t w = set.weight;
    if (hi - lo == 1 || (w <= targetWeight && (!fits || fitsNodes(&order[lo], hi - lo)))) {
      partHead[lo] = 1;
      return;
    }
    if (localOf && hi - lo <= kLocalNodes) {
      splitCopy(lo, hi);
      return;
    }
    uint64_t k = std::max<uint64_t>(2, (w + targetWeight - 1) / targetWeight);
    uint64_t kA = k / 2;
    uint64_t targetA = (w * kA + k / 2) / k;
    uint64_t maxA = w <= targetWeight ? w - 1 : kA * targetWeight;

    glm::vec3 extent = set.upper - set.lower;
    int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    auto before = [&](uint32_t a, uint32_t b) { return this->before(axis, a, b); };

    if (k > kMedianSplitParts) {
      // Large sets: a weighted median cut across the longest axis. It costs one selection instead of a
      // growth over half the set, and the halves run in parallel sooner; the growth cuts below it
      // make the parts connected.
      const uint32_t m = lo + uint32_t(uint64_t(hi - lo) * kA / k);
      medianCut(lo, hi, m - lo, axis, set.lower[axis], set.upper[axis], before);
      parallelForRanges(m - lo, threadsFor(lo, m), [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; i++) store(order[lo + i], m);
      });
      recurse(lo, m, hi);
      return;
    }
    const uint32_t inSet = hi, taken = hi | kTaken, queued = lo | kTaken;
    std::vector<uint32_t> sideA;  // in the order taken
    sideA.reserve(size_t(hi - lo) / 2 + 1);
    std::vector<uint32_t> seeds;  // the set sorted along the axis, made only when a component runs out
    size_t nextSeed = 0;
    uint32_t exhausted = 0;  // times the frontier ran out
    uint64_t wA = 0;
    // Frontier ordered by distance to the seed: regions grow round, not in the diamonds of BFS.
    std::vector<FrontierItem> frontier;  // a min-heap
    glm::vec3 origin(0.0f);
    auto take = [&](uint32_t node) {
      store(node, taken);
      sideA.push_back(node);
      wA += weights[node];
      for (uint32_t e = graph.offsets[node]; e < graph.offsets[node + 1]; e++) {
        uint32_t next = graph.adjacency[e];
        if (load(next) == inSet) {  // each node enters the frontier once: its distance never changes
          store(next, queued);
          const float distance = glm::distance(origin, positions[next]);
          uint32_t bits;
          std::memcpy(&bits, &distance, sizeof bits);
          frontier.push_back({uint64_t(bits) << 32 | id(next), next});
          std::push_heap(frontier.begin(), frontier.end(), std::greater<FrontierItem>());
        }
      }
    };
    const uint32_t seed = set.first[axis];
    origin = positions[seed];
    take(seed);
    while (wA < targetA) {
      if (frontier.empty()) {
        // Component exhausted: continue from the extreme node not yet taken. The first few times it is
        // found by a scan; a set that runs out more often (one of many small pieces) is sorted once.
        uint32_t next = UINT32_MAX;
        if (++exhausted <= kScannedSeeds) {
          for (uint32_t i = lo; i < hi; i++)
            if (load(order[i]) == inSet && (next == UINT32_MAX || before(order[i], next))) next = order[i];
        } else {
          if (seeds.empty()) {
            seeds.assign(order.begin() + lo, order.begin() + hi);
            std::sort(seeds.begin(), seeds.end(), before);
          }
          while (nextSeed < seeds.size() && load(seeds[nextSeed]) != inSet) nextSeed++;
          if (nextSeed < seeds.size()) next = seeds[nextSeed];
        }
        if (next == UINT32_MAX || wA + weights[next] > maxA) break;
        take(next);
        continue;
      }
      std::pop_heap(frontier.begin(), frontier.end(), std::greater<FrontierItem>());
      const uint32_t node = frontier.back().node;
      frontier.pop_back();
      if (wA + weights[node] <= maxA)
        take(node);
      else
        store(node, inSet);
    }
    for (const FrontierItem& f : frontier) store(f.node, inSet);  // left in the frontier: back to side B
    if (sideA.size() == hi - lo) {                                // never take everything
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

    recurse(lo, mid, hi);
  }

  // Splits set [lo, hi) as split() would, on a copy of its nodes and of the edges between them
  // (numbered in the set's order, ties broken by the graph's ids): every pass of the recursion below
  // then reads a few hundred kilobytes instead of gathering from arrays over the whole graph.
  void splitCopy(uint32_t lo, uint32_t hi) {
    const uint32_t m = hi - lo;
    std::vector<uint32_t> global(order.begin() + lo, order.begin() + hi);
    for (uint32_t i = 0; i < m; i++) (*localOf)[global[i]] = i;
    Graph copy;
    copy.offsets.resize(m + 1);
    std::vector<uint8_t> copyWeights(m);
    FillLaterVector<glm::vec3> copyPositions(m);
    for (uint32_t i = 0; i < m; i++) {
      const uint32_t node = global[i];
      copyWeights[i] = weights[node];
      copyPositions[i] = positions[node];
      for (uint32_t e = graph.offsets[node]; e < graph.offsets[node + 1]; e++) {
        const uint32_t next = graph.adjacency[e];
        if (load(next) == hi) copy.adjacency.push_back((*localOf)[next]);  // in this set
      }
      copy.offsets[i + 1] = uint32_t(copy.adjacency.size());
    }
    FillLaterVector<uint32_t> copyOrder;
    // Its halves of kParallelNodes or more still run as tasks of their own.
    Bisector local = over(copy, copyWeights, copyPositions, targetWeight, fits, copyOrder, threads);
    local.ids = global.data();
    local.split(0, m);
    for (uint32_t i = 0; i < m; i++) {
      order[lo + i] = global[copyOrder[i]];
      partHead[lo + i] = local.partHead[i];
    }
  }

  void recurse(uint32_t lo, uint32_t mid, uint32_t hi) {
    parallelInvoke(
        parallel && hi - lo >= kParallelNodes, [&] { split(lo, mid); }, [&] { split(mid, hi); });
  }
};

// Moves the fragments of parts (every connected piece but the largest) into the neighbouring part they
// share most edges with, when it has room and still fits; parts keep their order, moved nodes go last.
// A piece once moved is not looked at again, so a part's pieces at its turn are those it was made
// with. The turns run in part order, one after the other, but most of each is found beforehand: every
// fragment's neighbouring parts and fit checks are found on the threads against the parts as they are
// at the start. A turn takes those neighbours unless a node next to the fragment has moved since, and
// a check unless its answer may have changed (a part that fitted has gained nodes, or one that did
// not has lost some: the checks are monotonic): the same moves as asking everything at every turn.
void mergeFragments(const Graph& graph, const std::vector<uint8_t>& weights, uint32_t maxWeight,
                    const std::function<bool(const uint32_t*, size_t)>& fits, int threads, Partition& p) {
  const size_t n = p.order.size(), parts = p.partCount();
  // Part q's members: the first kept[q] of its run of p.order (a turn packs what stays to the front),
  // then those that arrived from other parts' turns.
  const std::vector<uint32_t> first = p.partStart;
  std::vector<uint32_t> kept(parts);
  std::vector<std::vector<uint32_t>> arrived(parts);
  FillLaterVector<uint32_t> owner(n);  // every node is in a part: all written below
  std::vector<uint64_t> weight(parts, 0);
  parallelFor(parts, threads, [&](size_t q) {
    kept[q] = first[q + 1] - first[q];
    for (uint32_t i = first[q]; i < first[q + 1]; i++) {
      owner[p.order[i]] = uint32_t(q);
      weight[q] += weights[p.order[i]];
    }
  });
  // The other parts a piece of q touches as (part, edges shared), most edges first; its neighbours in
  // them as (node, part) in `around` when given.
  auto neighbourParts = [&](uint32_t q, const std::vector<uint32_t>& piece,
                            std::vector<std::pair<uint32_t, uint32_t>>* around = nullptr) {
    std::vector<std::pair<uint32_t, uint32_t>> shared;
    for (uint32_t u : piece) {
      for (uint32_t e = graph.offsets[u]; e < graph.offsets[u + 1]; e++) {
        uint32_t r = owner[graph.adjacency[e]];
        if (r == q) continue;
        if (around) around->push_back({graph.adjacency[e], r});
        auto it = std::find_if(shared.begin(), shared.end(), [&](auto& x) { return x.first == r; });
        if (it == shared.end())
          shared.push_back({r, 1});
        else
          it->second++;
      }
    }
    std::sort(shared.begin(), shared.end(),
              [](auto& a, auto& b) { return a.second != b.second ? a.second > b.second : a.first < b.first; });
    return shared;
  };
  auto fitsWith = [&](uint32_t r, const std::vector<uint32_t>& piece) {
    if (!fits) return true;
    thread_local std::vector<uint32_t> merged;
    merged.assign(p.order.begin() + first[r], p.order.begin() + first[r] + kept[r]);
    merged.insert(merged.end(), arrived[r].begin(), arrived[r].end());
    merged.insert(merged.end(), piece.begin(), piece.end());
    return fits(merged.data(), merged.size());
  };
  // The part a fragment moves into: the first of `neighbours` with room for its weight `w` and for
  // which fitsIn(part) holds; UINT32_MAX where none.
  auto targetOf = [&](const std::vector<std::pair<uint32_t, uint32_t>>& neighbours, uint64_t w, auto&& fitsIn) {
    for (const auto& candidate : neighbours)
      if (weight[candidate.first] + w <= maxWeight && fitsIn(candidate.first)) return candidate.first;
    return UINT32_MAX;
  };
  struct Fragment {
    std::vector<uint32_t> nodes;
    uint64_t weight = 0;
    std::vector<std::pair<uint32_t, uint32_t>> neighbours, around;  // as at the start, or at its turn
    std::vector<std::pair<uint32_t, bool>> fitsIn;                  // (part, fits) as asked at the start
    bool moved = false;
  };
  struct PartInPieces {
    std::vector<Fragment> fragments;  // in the order the pieces were found
    std::vector<uint32_t> pieceOf;    // of each member of the part's run: its fragment, or kMainPiece
  };
  constexpr uint32_t kMainPiece = UINT32_MAX;
  // The connected pieces of each part, by flood fill in member order, on the threads; a part in
  // pieces keeps them, each with its neighbours and the checks its turn would ask as the parts are now.
  std::vector<PartInPieces> split(parts);
  FillLaterVector<uint32_t> piece = parallelFilled(n, UINT32_MAX, threads);
  parallelFor(parts, threads, [&](size_t q) {
    std::vector<std::vector<uint32_t>> pieces;
    const std::span<const uint32_t> members(&p.order[first[q]], first[q + 1] - first[q]);
    for (uint32_t start : members) {
      if (piece[start] != UINT32_MAX) continue;
      pieces.push_back({start});
      piece[start] = uint32_t(pieces.size() - 1);
      for (size_t h = 0; h < pieces.back().size(); h++) {
        uint32_t u = pieces.back()[h];
        for (uint32_t e = graph.offsets[u]; e < graph.offsets[u + 1]; e++) {
          uint32_t v = graph.adjacency[e];
          if (owner[v] == q && piece[v] == UINT32_MAX) {
            piece[v] = piece[u];
            pieces.back().push_back(v);
          }
        }
      }
    }
    if (pieces.size() < 2) return;
    size_t largest = 0;
    for (size_t i = 1; i < pieces.size(); i++)
      if (pieces[i].size() > pieces[largest].size()) largest = i;
    PartInPieces& s = split[q];
    s.pieceOf.resize(members.size());
    for (size_t k = 0; k < members.size(); k++) {
      const uint32_t i = piece[members[k]];
      s.pieceOf[k] = i == largest ? kMainPiece : uint32_t(i - (i > largest));
    }
    for (size_t i = 0; i < pieces.size(); i++) {
      if (i == largest) continue;
      Fragment& f = s.fragments.emplace_back();
      f.nodes = std::move(pieces[i]);
      for (uint32_t u : f.nodes) f.weight += weights[u];
      f.neighbours = neighbourParts(uint32_t(q), f.nodes, &f.around);
      targetOf(f.neighbours, f.weight, [&](uint32_t r) {  // the checks asked, not the target
        f.fitsIn.push_back({r, fitsWith(r, f.nodes)});
        return f.fitsIn.back().second;
      });
    }
  });
  FillLaterVector<uint32_t>().swap(piece);
  // Whether a turn moved nodes out of the part, into it.
  std::vector<uint8_t> lost(parts, 0), gained(parts, 0);
  bool anyMoved = false;
  for (uint32_t q = 0; q < parts; q++) {
    PartInPieces& s = split[q];
    bool movedHere = false;
    for (Fragment& f : s.fragments) {
      // A check asked before stands where the part has since only lost nodes (it fitted) or only
      // gained some (it did not).
      auto fitsIn = [&](uint32_t part) {
        const auto it = std::find_if(f.fitsIn.begin(), f.fitsIn.end(), [&](const auto& x) { return x.first == part; });
        const bool known = it != f.fitsIn.end() && (it->second ? !gained[part] : !lost[part]);
        return known ? it->second : fitsWith(part, f.nodes);
      };
      if (!std::all_of(f.around.begin(), f.around.end(), [&](const auto& x) { return owner[x.first] == x.second; }))
        f.neighbours = neighbourParts(q, f.nodes);
      const uint32_t r = targetOf(f.neighbours, f.weight, fitsIn);
      if (r == UINT32_MAX) continue;
      arrived[r].insert(arrived[r].end(), f.nodes.begin(), f.nodes.end());
      weight[r] += f.weight;
      weight[q] -= f.weight;
      gained[r] = lost[q] = 1;
      for (uint32_t u : f.nodes) owner[u] = r;
      f.moved = movedHere = true;
    }
    if (!movedHere) continue;
    // The members of the pieces kept, packed to the front of the part's run.
    uint32_t at = first[q];
    for (size_t k = 0; k < s.pieceOf.size(); k++)
      if (s.pieceOf[k] == kMainPiece || !s.fragments[s.pieceOf[k]].moved) p.order[at++] = p.order[first[q] + k];
    kept[q] = at - first[q];
    anyMoved = true;
  }
  if (!anyMoved) return;
  // The parts left with nodes, in order, each its kept run and then what arrived.
  std::vector<uint32_t> left;
  p.partStart.assign(1, 0);
  for (uint32_t q = 0; q < parts; q++)
    if (kept[q] + arrived[q].size() > 0) {
      left.push_back(q);
      p.partStart.push_back(p.partStart.back() + kept[q] + uint32_t(arrived[q].size()));
    }
  FillLaterVector<uint32_t> order(n);
  parallelFor(left.size(), threads, [&](size_t k) {
    const uint32_t q = left[k];
    std::copy(p.order.begin() + first[q], p.order.begin() + first[q] + kept[q], order.begin() + p.partStart[k]);
    std::copy(arrived[q].begin(), arrived[q].end(), order.begin() + p.partStart[k] + kept[q]);
  });
  p.order.swap(order);
}

}  // namespace

Partition partitionGraph(const Graph& graph, const std::vector<uint8_t>& weights,
                         const FillLaterVector<glm::vec3>& positions, uint32_t maxWeight, uint32_t targetWeight,
                         int threads, const std::function<bool(const uint32_t*, size_t)>& fits) {
  const uint32_t n = uint32_t(graph.nodeCount());
  Partition result;
  if (n == 0) return result;
  Bisector b = Bisector::over(graph, weights, positions, targetWeight, fits, result.order, threads);
  FillLaterVector<uint32_t> localOf;  // every entry written before it is read (splitCopy)
  if (n > kLocalNodes) {
    localOf.resize(n);
    b.localOf = &localOf;
  }
  if (threads > 1)
    withThreads(threads, [&] { b.split(0, n); });
  else
    b.split(0, n);
  const size_t heads = parallelNumber(
      n - 1, threads, [&](size_t i) { return b.partHead[i + 1] != 0; },
      [&](size_t total) { result.partStart.resize(total + 2); },
      [&](size_t i, size_t k) { result.partStart[k + 1] = uint32_t(i + 1); });
  result.partStart[heads + 1] = n;
  mergeFragments(graph, weights, maxWeight, fits, threads, result);
  return result;
}

}  // namespace vgeo
