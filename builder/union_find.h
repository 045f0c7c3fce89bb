// union_find.h: disjoint sets of 0 .. n - 1 with path halving. The smaller root wins every union, so
// the sets' representatives do not depend on the order of the unions (builds stay deterministic), and
// unite() and find() may run on many threads at once: a word changes by compare-and-swap, and every
// change keeps the relation it states true.
// With kParity each element also has a turn relative to its set's representative (orientation: faces
// walking a shared edge the same way must differ), and the word is parent << 1 | turn relative to the
// parent, so such a set holds fewer than 2^31 elements.
#pragma once

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "../common/parallel.h"

namespace vgeo {

template <bool kParity>
class BasicUnionFind {
 public:
  explicit BasicUnionFind(size_t n, int threads = 1) : words_(n) {
    parallelForRanges(n, threads, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; i++) words_[i] = uint32_t(i) << kShift;
    });
  }
  uint32_t find(uint32_t x) { return findWithTurn(x).first; }
  // The representative of x's set and x's turn relative to it (0 without kParity).
  std::pair<uint32_t, uint8_t> findWithTurn(uint32_t x) {
    uint8_t turn = 0;
    for (;;) {
      uint32_t w = load(x), parent = w >> kShift;
      if (parent == x) return {x, turn};
      uint32_t up = load(parent), grand = up >> kShift;
      uint32_t expected = w;
      if (grand != parent)  // path halving: x's relation to its grandparent holds as well
        __atomic_compare_exchange_n(&words_[x], &expected, grand << kShift | ((w ^ up) & kTurn), false,
                                    __ATOMIC_RELAXED, __ATOMIC_RELAXED);
      turn ^= uint8_t(w & kTurn);
      x = parent;
    }
  }
  // Joins the sets of a and b, a's turn differing from b's when `differ` (kParity only); false when
  // they were joined already with the opposite relation.
  bool unite(uint32_t a, uint32_t b, bool differ = false) {
    for (;;) {
      auto [ra, ta] = findWithTurn(a);
      auto [rb, tb] = findWithTurn(b);
      const uint32_t relation = (uint32_t(differ) ^ ta ^ tb) & kTurn;  // turn of ra relative to rb
      if (ra == rb) return relation == 0;
      const uint32_t high = std::max(ra, rb), low = std::min(ra, rb);
      uint32_t expected = high << kShift;  // still a root
      if (__atomic_compare_exchange_n(&words_[high], &expected, low << kShift | relation, false, __ATOMIC_RELAXED,
                                      __ATOMIC_RELAXED))
        return true;
    }
  }

 private:
  static constexpr uint32_t kShift = kParity ? 1u : 0u, kTurn = kParity ? 1u : 0u;
  uint32_t load(uint32_t x) const { return __atomic_load_n(&words_[x], __ATOMIC_RELAXED); }
  FillLaterVector<uint32_t> words_;
};
using UnionFind = BasicUnionFind<false>;
using ParityUnionFind = BasicUnionFind<true>;

}  // namespace vgeo
