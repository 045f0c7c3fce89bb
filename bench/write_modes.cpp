// write_modes.cpp: how a machine's disk takes a file written and then fsynced, to tell what part of
// `vgeo build`'s write is the disk (CHANGELOG.md, 2026-11-28). Writes 19, 75 and 250 MB four ways, three rounds:
// 4 MB writes each followed by a writeback hint (sync_file_range), 1 MB writes then fsync alone, 1 MB
// writes then one hint over the whole file, and 1 MB writes each followed by its hint; and, for scale,
// a copy into fresh memory. Build: g++ -O2 -static -o write_modes bench/write_modes.cpp; run:
// ./write_modes DIR.
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

using Clock = std::chrono::steady_clock;
static double ms(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: write_modes DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  std::vector<char> source(size_t(256) << 20);
  for (size_t i = 0; i < source.size(); i++) source[i] = char(i * 2654435761u >> 13);
  const char* names[] = {"4MB+hint", "1MB,fsync", "1MB,hint-all", "1MB+hint"};
  for (int round = 0; round < 3; round++)
    for (size_t mb : {19, 75, 250}) {
      const size_t bytes = mb << 20;
      for (int mode = 0; mode < 4; mode++) {
        const std::string path = dir + "/write_modes_" + std::to_string(mode) + ".bin";
        ::unlink(path.c_str());
        const auto t0 = Clock::now();
        const int fd = ::open(path.c_str(), O_CREAT | O_TRUNC | O_WRONLY, 0644);
        const size_t chunk = mode == 0 ? (4 << 20) : (1 << 20);
        for (size_t at = 0, sent = 0; at < bytes; at += chunk) {
          const size_t n = std::min(chunk, bytes - at);
          if (::pwrite(fd, source.data() + at, n, off_t(at)) != ssize_t(n)) return std::perror("pwrite"), 1;
          if (mode == 0 || mode == 3) {
            ::sync_file_range(fd, off_t(sent), off_t(at + n - sent), SYNC_FILE_RANGE_WRITE);
            sent = at + n;
          }
        }
        const auto t1 = Clock::now();
        if (mode == 2) ::sync_file_range(fd, 0, off_t(bytes), SYNC_FILE_RANGE_WRITE);
        const auto t2 = Clock::now();
        ::fsync(fd);
        ::close(fd);
        ::unlink(path.c_str());
        const auto t3 = Clock::now();
        std::printf("round %d %4zu MB %-12s write %7.2f  hint %6.2f  fsync %7.2f  total %7.2f ms\n", round, mb,
                    names[mode], ms(t0, t1), ms(t1, t2), ms(t2, t3), ms(t0, t3));
      }
      const auto t0 = Clock::now();
      char* fresh = static_cast<char*>(std::malloc(bytes));
      std::memcpy(fresh, source.data(), bytes);
      const auto t1 = Clock::now();
      std::printf("round %d %4zu MB copy into fresh memory %.2f ms (%d)\n", round, mb, ms(t0, t1), fresh[bytes / 2]);
      std::free(fresh);
    }
}
