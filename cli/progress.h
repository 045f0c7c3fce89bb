// progress.h: a one-line progress bar on stderr, shown only on a terminal, only without --quiet, and
// only once the work has taken more than a second (short builds stay silent).
#pragma once

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

namespace vgeo {

class ProgressBar {
 public:
  explicit ProgressBar(bool quiet)
      : enabled_(!quiet && isatty(STDERR_FILENO)), start_(std::chrono::steady_clock::now()) {}
  ~ProgressBar() { finish(); }

  void update(double fraction, const char* stage) {
    if (!enabled_) return;
    double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (elapsed < 1.0) return;
    int filled = int(fraction * 30.0 + 0.5);
    filled = filled < 0 ? 0 : filled > 30 ? 30 : filled;
    std::fprintf(stderr, "\r[%s%s] %3d%% %-12s %5.1fs", std::string(size_t(filled), '#').c_str(),
                 std::string(size_t(30 - filled), '.').c_str(), int(fraction * 100.0 + 0.5), stage, elapsed);
    std::fflush(stderr);
    shown_ = true;
  }
  void finish() {
    if (shown_) std::fprintf(stderr, "\r%60s\r", "");
    shown_ = false;
  }

 private:
  bool enabled_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace vgeo
