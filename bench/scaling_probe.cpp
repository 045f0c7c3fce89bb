// scaling_probe.cpp: how far a machine lets a workload speed up from one thread to many, to tell what
// part of the builder's 1 -> 16 thread speed-up the hardware allows (bench/README.md, "Against the peer builders").
// Weak scaling: each of T threads runs the same work, alone in its data, so the speed-up T * t(1) / t(T) is T for a
// machine whose cores do not slow each other down. Four kinds of work, the builder's in miniature:
// arithmetic in registers (the clock as more cores run), a stream over 64 MB (memory bandwidth), a
// random walk over 4 MB (misses past the core's own cache), and fresh memory touched a page at a time
// (the kernel's page faults, dear in a virtual machine). The best of two runs for each T.
// Build: g++ -O2 -pthread -static -o scaling_probe bench/scaling_probe.cpp; run: ./scaling_probe.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <utility>
#include <vector>

namespace {

std::atomic<uint64_t> sink{0};  // every result lands here (an atomic's updates are kept), so no work is dropped

void arithmetic(int) {
  uint64_t a = 1, b = 2, c = 3, d = 4;
  for (int i = 0; i < 150000000; i++) {
    a ^= a << 13, a ^= a >> 7, a ^= a << 17;
    b = b * 6364136223846793005ull + 1;
    c += a ^ b;
    d ^= c + (d << 3);
  }
  sink += a + b + c + d;
}

void stream(int) {
  std::vector<uint64_t> v(size_t(8) << 20, 1);  // 64 MB
  uint64_t s = 0;
  for (int round = 0; round < 12; round++)
    for (uint64_t& x : v) s += x, x = s;
  sink += s;
}

void randomWalk(int thread) {
  const size_t n = size_t(1) << 20;  // 4 MB of links: one cycle in a random order
  std::vector<uint32_t> next(n);
  for (size_t i = 0; i < n; i++) next[i] = uint32_t(i);
  uint64_t x = 88172645463325252ull + uint64_t(thread);
  for (size_t i = n - 1; i > 0; i--) {
    x ^= x << 13, x ^= x >> 7, x ^= x << 17;
    std::swap(next[i], next[x % (i + 1)]);
  }
  uint32_t at = 0;
  for (int i = 0; i < 40000000; i++) at = next[at];
  sink += at;
}

void freshPages(int) {
  const size_t bytes = size_t(64) << 20;
  for (int round = 0; round < 6; round++) {
    char* p = static_cast<char*>(std::malloc(bytes));  // above glibc's mmap threshold: new pages each time
    for (size_t i = 0; i < bytes; i += 4096) p[i] = 1;
    sink += uint64_t(p[4096]);
    std::free(p);
  }
}

double seconds() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

}  // namespace

int main() {
  const struct {
    const char* name;
    void (*work)(int);
  } kinds[] = {
      {"arithmetic", arithmetic}, {"stream-64MB", stream}, {"walk-4MB", randomWalk}, {"fresh-pages", freshPages}};
  const int most = int(std::max(1u, std::thread::hardware_concurrency()));
  for (const auto& kind : kinds) {
    double one = 0.0;
    for (int threads = 1; threads <= most; threads = threads < 4 ? threads * 2 : threads + 4) {
      double best = 1e30;
      for (int run = 0; run < 2; run++) {
        const double start = seconds();
        std::vector<std::thread> pool;
        for (int t = 0; t < threads; t++) pool.emplace_back(kind.work, t);
        for (std::thread& t : pool) t.join();
        best = std::min(best, seconds() - start);
      }
      if (threads == 1) one = best;
      std::printf("%-12s %3d threads %7.3f s  speed-up %5.2f\n", kind.name, threads, best, threads * one / best);
      std::fflush(stdout);
    }
  }
}
