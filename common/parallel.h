// parallel.h: the builder's parallel loops and sorts on oneTBB's task scheduler (Debian libtbb-dev): one
// pool of worker threads for the whole run, work stolen between them, and `threads` capping how many
// take part (a task arena of that size). Results never depend on scheduling: loop bodies write to slot
// i of their output, and sorts take orders in which no two distinguishable elements are equal, so a
// parallel sort gives exactly std::sort's result and the output is the same whatever `threads`.
#pragma once

#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <functional>
#include <mutex>
#include <type_traits>
#include <vector>

#include "fill_later.h"

namespace vgeo {

// The arenas are made once for each size and kept for the run (never freed: they outlive every
// caller): an arena made for each parallel loop cost tens of microseconds a loop, and a build runs
// hundreds of loops, most of them short.
inline tbb::task_arena& arenaOfSize(int concurrency) {
  static std::mutex lock;
  // By size; the list too is never freed, so that the arenas stay reachable (no leak to report).
  static std::vector<tbb::task_arena*>& arenas = *new std::vector<tbb::task_arena*>();
  const std::lock_guard<std::mutex> hold(lock);
  if (arenas.size() <= size_t(concurrency)) arenas.resize(size_t(concurrency) + 1, nullptr);
  if (!arenas[size_t(concurrency)]) arenas[size_t(concurrency)] = new tbb::task_arena(concurrency);
  return *arenas[size_t(concurrency)];
}
// Runs fn() with at most `threads` threads (the caller's among them) for the parallel calls inside it;
// no more than the machine has (oneTBB warns on stderr when asked for more, and results do not depend
// on the count).
template <class Fn>
void withThreads(int threads, Fn&& fn) {
  arenaOfSize(std::clamp(threads, 1, std::max(tbb::info::default_concurrency(), 1))).execute(std::forward<Fn>(fn));
}

// fn(i) for every i in [0, count), on up to `threads` threads; an exception thrown by fn stops the
// loop and is rethrown here.
template <class Fn>
void parallelFor(size_t count, int threads, Fn&& fn) {
  if (threads <= 1 || count <= 1) {
    for (size_t i = 0; i < count; i++) fn(i);
    return;
  }
  withThreads(threads, [&] { tbb::parallel_for(size_t(0), count, [&](size_t i) { fn(i); }); });
}

// fn(i) for every i in [0, count), on up to `threads` threads, each thread taking the next i as it
// gets free: for few, heavy items of unequal cost, listed heaviest first, so that none of the heavy
// ones is left to start last. While items are still running, a thread with none left to take calls
// fill() until it returns false or the last item is done: for work wanted later, a short piece a
// call, done by the threads that would wait on the loop's last items. An exception thrown by fn stops
// the loop and is rethrown here.
template <class Fn, class Fill>
void parallelForInOrder(size_t count, int threads, Fn&& fn, Fill&& fill) {
  if (threads <= 1 || count == 0) {
    for (size_t i = 0; i < count; i++) fn(i);
    return;
  }
  std::atomic<size_t> next{0}, running{count};
  withThreads(threads, [&] {
    tbb::parallel_for(
        0, threads,
        [&](int) {
          for (size_t i = next++; i < count && !tbb::is_current_task_group_canceling(); i = next++) {
            fn(i);
            running--;
          }
          while (running.load(std::memory_order_relaxed) > 0 && !tbb::is_current_task_group_canceling() && fill()) {
          }
        },
        tbb::simple_partitioner());
  });
}
template <class Fn>
void parallelForInOrder(size_t count, int threads, Fn&& fn) {
  parallelForInOrder(count, count > 1 ? threads : 1, std::forward<Fn>(fn), [] { return false; });
}

// Lowers `target` to `value` when smaller, from any thread (the smallest of all offered wins).
template <class T>
void atomicMin(T& target, T value) {
  T seen = __atomic_load_n(&target, __ATOMIC_RELAXED);
  while (value < seen &&
         !__atomic_compare_exchange_n(&target, &seen, value, false, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) {
  }
}

// fn(begin, end) over [0, count) in ranges of kParallelRange (or `range`) on up to `threads` threads:
// for loops whose body is too small to be a task of its own.
constexpr size_t kParallelRange = 16384;
// The range for bodies of a microsecond or more an element (a vertex's ring walked and sorted): in
// ranges of kParallelRange a mesh of 100,000 vertices would give 16 threads six ranges.
constexpr size_t kHeavyRange = 1024;
inline size_t parallelRangeCount(size_t count, size_t range = kParallelRange) { return (count + range - 1) / range; }
template <class Fn>
void parallelForRanges(size_t count, int threads, Fn&& fn, size_t range = kParallelRange) {
  parallelFor(parallelRangeCount(count, range), threads,
              [&](size_t r) { fn(r * range, std::min(count, (r + 1) * range)); });
}

// fn(begin, end) for each run [begin, end) of [0, count) whose neighbours are alike (same(i - 1, i)),
// on up to `threads` threads: for passes over sorted records, a key's records handled together. With a
// third parameter fn also gets the index of the range the run starts in (parallelRangeCount(count) of
// them, in order), for output kept a range at a time and joined in order.
template <class Same, class Fn>
void parallelForRuns(size_t count, int threads, Same&& same, Fn&& fn) {
  parallelForRanges(count, threads, [&](size_t begin, size_t end) {
    size_t i = begin;  // the runs that start in [begin, end), read to their ends
    while (i > 0 && i < end && same(i - 1, i)) i++;
    while (i < end) {
      size_t j = i + 1;
      while (j < count && same(j - 1, j)) j++;
      if constexpr (std::is_invocable_v<Fn, size_t, size_t, size_t>)
        fn(i, j, begin / kParallelRange);
      else
        fn(i, j);
      i = j;
    }
  });
}

// The prefix sums of weight(i) over [0, count), on up to `threads` threads: weighed a block at a time,
// then sized(total) is called, then visit(i, n, w) for every i in order, with its weight w and n the
// sum of the weights before it (weight(i) is read before visit(i, ...), which may change what it
// read). Returns the total.
template <class Weight, class Sized, class Visit>
size_t parallelPrefix(size_t count, int threads, Weight&& weight, Sized&& sized, Visit&& visit,
                      size_t range = kParallelRange) {
  const size_t blocks = parallelRangeCount(count, range);
  std::vector<size_t> base(blocks + 1, 0);
  parallelForRanges(
      count, threads,
      [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; i++) base[begin / range + 1] += size_t(weight(i));
      },
      range);
  for (size_t k = 0; k < blocks; k++) base[k + 1] += base[k];
  sized(base[blocks]);
  parallelForRanges(
      count, threads,
      [&](size_t begin, size_t end) {
        size_t n = base[begin / range];
        for (size_t i = begin; i < end; i++) {
          const size_t w = size_t(weight(i));
          visit(i, n, w);
          n += w;
        }
      },
      range);
  return base[blocks];
}

// Numbers the elements of [0, count) in order, each taking weight(i) numbers (a bool: one when it is
// picked): parallelPrefix, with number(i, n) for each i of non-zero weight and the first of its
// numbers. Returns the total.
template <class Weight, class Sized, class Number>
size_t parallelNumber(size_t count, int threads, Weight&& weight, Sized&& sized, Number&& number) {
  return parallelPrefix(count, threads, weight, sized, [&](size_t i, size_t n, size_t w) {
    if (w) number(i, n);
  });
}

// `count` copies of `value`, written on up to `threads` threads.
template <class T>
FillLaterVector<T> parallelFilled(size_t count, const T& value, int threads) {
  FillLaterVector<T> v(count);
  parallelForRanges(count, threads, [&](size_t begin, size_t end) {
    std::fill(v.begin() + long(begin), v.begin() + long(end), value);
  });
  return v;
}

// a() and b(), side by side when `together` (inside withThreads, on its threads), else one after the
// other: for divide-and-conquer work whose halves are independent. Side by side, oneTBB runs b() on
// the calling thread and a() as a task another thread may take.
template <class A, class B>
void parallelInvoke(bool together, A&& a, B&& b) {
  if (together) {
    tbb::parallel_invoke(std::forward<A>(a), std::forward<B>(b));
  } else {
    a();
    b();
  }
}

// std::sort's result on up to `threads` threads; `less` must be a strict total order on the elements
// that can be told apart (equal elements must be identical), or the result would depend on the schedule.
template <class T, class Less = std::less<T>>
void parallelSort(std::vector<T>& v, int threads, Less less = Less()) {
  if (threads <= 1 || v.size() < 65536) {
    std::sort(v.begin(), v.end(), less);
    return;
  }
  withThreads(threads, [&] { tbb::parallel_sort(v.begin(), v.end(), less); });
}

}  // namespace vgeo
