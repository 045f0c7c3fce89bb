// bucket_sort.h: the builder's large sorts (tens of millions of edges or faces) as a counting pass into
// buckets by the top bits of a key, then a sort of each bucket (an MSD radix step, then std::sort).
// Each pass runs on all threads: counting and placing over chunks of the input, each chunk with its
// own counts, then the buckets' sorts; a comparison sort of the whole array starts with partitions on
// one thread, which kept 16 threads at a few times the speed of one. Buckets are few enough that the
// counts stay in cache and placing writes one stream a bucket. The caller's generator makes the items
// twice (once counted, once placed), so no unsorted copy is held next to the sorted one.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "parallel.h"

namespace vgeo {

// Keys for items whose order between buckets does not matter, only that equal ones meet: a hash of
// 32-bit words in order (FNV-1a, finished by a mix so that its top bits spread), and of a set of
// distinct words in any order (a sum of mixed words, no sort needed).
inline uint64_t mixBits(uint64_t x) {  // splitmix64's finalizer
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}
inline uint64_t hashWords(const uint32_t* words, size_t count) {
  uint64_t h = 1469598103934665603ull;
  for (size_t i = 0; i < count; i++) h = (h ^ words[i]) * 1099511628211ull;
  return mixBits(h);
}
inline uint64_t hashOfSet(const uint32_t* words, size_t count) {
  uint64_t h = mixBits(count);
  for (size_t i = 0; i < count; i++) h += mixBits(words[i] + 0x9e3779b97f4a7c15ull);
  return h;
}

// The items that make(s, emit) emits as emit(key, item) for every source s in [0, sources), sorted by
// the top `bucketBits` of their keys (below 2^keyBits), then by `less`: exactly by `less` where the key
// never decreases along it. With a strict order in which no two distinguishable items are equal, the
// result does not depend on `threads`. `starts`, when given, receives where each bucket begins (one
// more entry, the end). Up to kChunkedBucketBits, each chunk of sources counts into buckets of its own
// (hashed keys, scattered over memory: the counts must stay in cache). Finer buckets (a bucket a
// vertex id, or about an item a bucket of hashed keys, so that a bucket costs next to no sort) are
// counted twice: first by their top bits as above, each item placed with the bits below beside it
// (8, or more where the top ones would be over kChunkedBucketBits, up to kMaxFineBits), then each of
// those buckets into its finer ones, a bucket a task. Beyond, one row of counts shared by all threads
// (atomic increments where there are several). The shared row cost 16 threads 3.6 times one thread's
// work (a locked increment that misses the cache cannot overlap the next); a bucket sorted by `less`
// instead of counted again cost one thread 30% more.
constexpr int kChunkedBucketBits = 14;
constexpr int kMaxFineBits = 16;
template <class T, class Make, class Less>
FillLaterVector<T> bucketSorted(size_t sources, int keyBits, int bucketBits, int threads, Make&& make, Less&& less,
                                FillLaterVector<size_t>* starts = nullptr) {
  bucketBits = std::min(bucketBits, keyBits);
  const int shift = keyBits - bucketBits;
  // The first pass's buckets: the top bits, the `fineBits` below them counted in a second pass.
  const int over = bucketBits - kChunkedBucketBits;
  const int fineBits = over > 0 && over <= kMaxFineBits ? std::max(over, std::min(8, bucketBits - 8)) : 0;
  const int firstShift = shift + fineBits;
  const size_t buckets = size_t(1) << (bucketBits - fineBits);
  const bool shared = bucketBits - fineBits > kChunkedBucketBits;
  const size_t chunks = shared ? 1 : std::max<size_t>(1, std::min(sources, size_t(std::max(threads, 1)) * 4));
  auto chunkBegin = [&](size_t c) { return sources * c / chunks; };
  // Shared: any source on any thread; chunked: chunk c's sources on one.
  auto forSources = [&](auto&& body) {
    if (shared)
      parallelFor(sources, threads, [&](size_t s) { body(0, s); });
    else
      parallelFor(chunks, threads, [&](size_t c) {
        for (size_t s = chunkBegin(c); s < chunkBegin(c + 1); s++) body(c, s);
      });
  };
  const bool atomic = shared && threads > 1;
  auto claim = [&](size_t& slot) { return atomic ? __atomic_fetch_add(&slot, size_t(1), __ATOMIC_RELAXED) : slot++; };
  // next[c * buckets + b]: chunk c's count in bucket b, then where its next item there goes.
  FillLaterVector<size_t> next = parallelFilled(chunks * buckets, size_t(0), threads);
  forSources([&](size_t c, size_t s) {
    make(s, [&](uint64_t key, const T&) { claim(next[c * buckets + size_t(key >> firstShift)]); });
  });
  FillLaterVector<size_t> bucketStart(buckets + 1);
  if (chunks == 1) {
    // One row of counts (up to a bucket a vertex): its prefix sums, on the threads.
    bucketStart[buckets] = parallelPrefix(
        buckets, threads, [&](size_t b) { return next[b]; }, [](size_t) {},
        [&](size_t b, size_t at, size_t) { bucketStart[b] = next[b] = at; });
  } else {
    // Bucket b's items go in chunk order. The counts (a row a chunk) are read a block of buckets at a
    // time, the block's part of each row in turn (a walk down one bucket's column missed the cache on
    // every step), the blocks on the threads: with many threads there are many rows, so there are
    // blocks enough for every thread (256 to 2,048 buckets).
    const size_t block = std::clamp<size_t>(buckets / size_t(std::max(threads, 1)), 256, 2048);
    const size_t blocks = (buckets + block - 1) / block;
    auto blockEnd = [&](size_t k) { return std::min(buckets, (k + 1) * block); };
    bucketStart[0] = 0;
    parallelFor(blocks, threads, [&](size_t k) {
      std::fill(bucketStart.begin() + long(k * block) + 1, bucketStart.begin() + long(blockEnd(k)) + 1, size_t(0));
      for (size_t c = 0; c < chunks; c++)
        for (size_t b = k * block; b < blockEnd(k); b++) bucketStart[b + 1] += next[c * buckets + b];
    });
    for (size_t b = 0; b < buckets; b++) bucketStart[b + 1] += bucketStart[b];
    parallelFor(blocks, threads, [&](size_t k) {
      std::vector<size_t> at(bucketStart.begin() + long(k * block), bucketStart.begin() + long(blockEnd(k)));
      for (size_t c = 0; c < chunks; c++)
        for (size_t b = k * block; b < blockEnd(k); b++) {
          const size_t n = next[c * buckets + b];
          next[c * buckets + b] = at[b - k * block];
          at[b - k * block] += n;
        }
    });
  }
  FillLaterVector<T> sorted(bucketStart[buckets]);  // every slot written by the placing pass
  FillLaterVector<uint16_t> fine(fineBits ? sorted.size() : 0);
  const uint64_t fineMask = (uint64_t(1) << fineBits) - 1;
  forSources([&](size_t c, size_t s) {
    make(s, [&](uint64_t key, const T& item) {
      const size_t at = claim(next[c * buckets + size_t(key >> firstShift)]);
      sorted[at] = item;
      if (fineBits) fine[at] = uint16_t((key >> shift) & fineMask);
    });
  });
  FillLaterVector<size_t>().swap(next);
  if (!fineBits) {
    parallelFor(buckets, threads, [&](size_t b) {  // a task a bucket: 16,384 buckets are one range of a loop
      if (bucketStart[b + 1] - bucketStart[b] > 1)
        std::sort(sorted.begin() + long(bucketStart[b]), sorted.begin() + long(bucketStart[b + 1]), less);
    });
    if (starts) *starts = std::move(bucketStart);
    return sorted;
  }
  // Each first bucket counted into its finer ones (in place order, which keeps chunk order), then each
  // of those sorted.
  const size_t fineBuckets = size_t(1) << fineBits;
  if (starts) {
    starts->resize((buckets << fineBits) + 1);
    (*starts)[buckets << fineBits] = sorted.size();
  }
  parallelFor(buckets, threads, [&](size_t b) {
    const size_t begin = bucketStart[b], end = bucketStart[b + 1];
    thread_local std::vector<size_t> at;
    thread_local std::vector<T> moved;
    at.assign(fineBuckets + 1, 0);
    for (size_t i = begin; i < end; i++) at[fine[i] + 1]++;
    for (size_t k = 0; k < fineBuckets; k++) at[k + 1] += at[k];
    if (starts)
      for (size_t k = 0; k < fineBuckets; k++) (*starts)[(b << fineBits) + k] = begin + at[k];
    if (end - begin > 1) {
      moved.resize(end - begin);
      for (size_t i = begin; i < end; i++) moved[at[fine[i]]++] = sorted[i];
      std::copy(moved.begin(), moved.end(), sorted.begin() + long(begin));
      for (size_t k = 0, from = 0; k < fineBuckets; from = at[k], k++)
        if (at[k] - from > 1)
          std::sort(sorted.begin() + long(begin + from), sorted.begin() + long(begin + at[k]), less);
    }
  });
  return sorted;
}

// Bits to hold values below `end`.
inline int bitsFor(uint64_t end) {
  int bits = 0;
  while (bits < 64 && (end - 1) >> bits) bits++;
  return bits;
}

}  // namespace vgeo
