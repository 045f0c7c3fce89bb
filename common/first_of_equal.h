// first_of_equal.h: for each of n items, the first item equal to it, by one concurrent hash table
// (open addressing, linear probing) filled and then read on the threads. Repair welds positions this
// way, and a subdivided cage's limit positions are checked for repeats: a table of 8-byte entries at
// most half full takes fewer trips through memory than a sort of every item's key (three). An entry holds the
// top half of the item's hash beside its id; an item goes to the first slot from its hash's home that
// is empty or holds an item equal to it, where the smaller id stays (a compare-and-swap). Equal items
// have one hash and so one probe sequence, and a slot once taken keeps its class of items, so the
// result is the smallest equal id whatever the threads' order.
#pragma once

#include <algorithm>
#include <cstdint>

#include "parallel.h"

namespace vgeo {

// first[i] = the smallest j with equal(i, j), for i in [0, count) (count below 2^32). hash(i) must be
// the same for equal items and spread over its 64 bits (mixBits); equal must be an equivalence.
template <class Hash, class Equal>
FillLaterVector<uint32_t> firstOfEqual(size_t count, int threads, Hash&& hash, Equal&& equal) {
  constexpr uint64_t kEmpty = ~uint64_t(0);
  size_t capacity = 1024;
  while (capacity < 2 * count) capacity *= 2;
  const size_t mask = capacity - 1;
  FillLaterVector<uint64_t> slots = parallelFilled(capacity, kEmpty, threads);
  auto entry = [](uint64_t h, size_t i) { return (h >> 32) << 32 | uint64_t(i); };
  auto sameClass = [&](uint64_t e, uint64_t h, size_t i) {
    return e >> 32 == h >> 32 && equal(size_t(uint32_t(e)), i);
  };
  // Items a batch at a time, their home slots asked for first, so that the cache misses overlap.
  constexpr size_t kBatch = 32;
  auto batches = [&](auto&& visit) {
    parallelForRanges(count, threads, [&](size_t begin, size_t end) {
      uint64_t hashes[kBatch];
      for (size_t b = begin; b < end; b += kBatch) {
        const size_t n = std::min(kBatch, end - b);
        for (size_t k = 0; k < n; k++) {
          hashes[k] = hash(b + k);
          __builtin_prefetch(&slots[size_t(hashes[k]) & mask]);
        }
        for (size_t k = 0; k < n; k++) visit(b + k, hashes[k]);
      }
    });
  };
  batches([&](size_t i, uint64_t h) {
    const uint64_t mine = entry(h, i);
    for (size_t s = size_t(h) & mask;; s = (s + 1) & mask) {
      uint64_t e = __atomic_load_n(&slots[s], __ATOMIC_RELAXED);
      if (e == kEmpty && __atomic_compare_exchange_n(&slots[s], &e, mine, false, __ATOMIC_RELAXED, __ATOMIC_RELAXED))
        return;
      if (!sameClass(e, h, i)) continue;  // taken by another class (a failed exchange read the taker)
      while (uint32_t(e) > i &&
             !__atomic_compare_exchange_n(&slots[s], &e, mine, false, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) {
      }
      return;
    }
  });
  FillLaterVector<uint32_t> first(count);
  batches([&](size_t i, uint64_t h) {
    size_t s = size_t(h) & mask;
    while (!sameClass(slots[s], h, i)) s = (s + 1) & mask;
    first[i] = uint32_t(slots[s]);
  });
  return first;
}

}  // namespace vgeo
