// union_find.h: disjoint sets of 0 .. n - 1 with path halving. The smaller root wins every union, so
// the sets' representatives do not depend on the order of the unions (builds stay deterministic).
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
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void unite(uint32_t a, uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<uint32_t> parent_;
};

}  // namespace vgeo
