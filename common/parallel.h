// parallel.h: a parallel for over indices with a fixed number of threads. Work is claimed one index at a
// time from an atomic counter; callers write results to slot i, so output never depends on scheduling.
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace vgeo {

template <class Fn>
void parallelFor(size_t count, int threads, Fn&& fn) {
  if (threads <= 1 || count <= 1) {
    for (size_t i = 0; i < count; i++) fn(i);
    return;
  }
  std::atomic<size_t> next{0};
  std::exception_ptr error;
  std::mutex errorLock;
  auto work = [&] {
    try {
      for (size_t i; (i = next.fetch_add(1)) < count;) fn(i);
    } catch (...) {
      std::lock_guard<std::mutex> lock(errorLock);
      if (!error) error = std::current_exception();
      next = count;
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads && size_t(t) < count; t++) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

// std::sort on two threads: each half sorted apart, then merged. Same result as std::sort for a strict
// weak order on distinct-or-equal elements (equal elements are indistinguishable here).
template <class T>
void parallelSort(std::vector<T>& v, int threads) {
  if (threads <= 1 || v.size() < 65536) {
    std::sort(v.begin(), v.end());
    return;
  }
  auto mid = v.begin() + long(v.size() / 2);
  std::thread other([&] { std::sort(v.begin(), mid); });
  std::sort(mid, v.end());
  other.join();
  std::inplace_merge(v.begin(), mid, v.end());
}

}  // namespace vgeo
