// union_find.h: disjoint sets of 0 .. n - 1 with path halving. The smaller root wins every union, so
// the sets' representatives do not depend on the order of the unions (builds stay deterministic), and
// unite() and find() may run on many threads at once: a parent changes by compare-and-swap, and a
// change keeps every element's representative what it was or makes it one of a joined set.
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace vgeo {

class UnionFind {
 public:
  explicit UnionFind(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0u); }
  uint32_t find(uint32_t x) {
    for (;;) {
      uint32_t parent = load(x);
      if (parent == x) return x;
      uint32_t grand = load(parent);
      if (grand != parent)
        __atomic_compare_exchange_n(&parent_[x], &parent, grand, false, __ATOMIC_RELAXED, __ATOMIC_RELAXED);
      x = grand;
    }
  }
  void unite(uint32_t a, uint32_t b) {
    for (;;) {
      a = find(a);
      b = find(b);
      if (a == b) return;
      uint32_t high = std::max(a, b), expected = high;  // still a root
      if (__atomic_compare_exchange_n(&parent_[high], &expected, std::min(a, b), false, __ATOMIC_RELAXED,
                                      __ATOMIC_RELAXED))
        return;
    }
  }

 private:
  uint32_t load(uint32_t x) const { return __atomic_load_n(&parent_[x], __ATOMIC_RELAXED); }
  std::vector<uint32_t> parent_;
};

}  // namespace vgeo
