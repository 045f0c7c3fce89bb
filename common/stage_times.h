// stage_times.h: wall time per named step of a run (the builder's `--stats` "stage_seconds"), so a
// benchmark says where the time went and which steps keep a run from scaling with threads.
#pragma once

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace vgeo {

struct StageTimes {
  std::vector<std::pair<std::string, double>> seconds;  // in the order the stages first ran
  void add(const std::string& stage, double s) {
    for (auto& [name, total] : seconds)
      if (name == stage) {
        total += s;
        return;
      }
    seconds.push_back({stage, s});
  }
};

// Adds the time since its start to `stage` of `times` (if any) when it is stopped or destroyed.
class StageTimer {
 public:
  StageTimer(StageTimes* times, const char* stage) : times_(times), stage_(stage) {}
  ~StageTimer() { stop(); }
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;
  void stop() {
    if (!times_) return;
    times_->add(stage_, std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
    times_ = nullptr;
  }

 private:
  StageTimes* times_;
  const char* stage_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// Runs step() as stage `stage` of `times` (nullptr: untimed) and returns what it returns, so that a
// function reads as its steps: `auto mesh = timed(times, "load", [&] { return load(path); });`.
template <class Step>
decltype(auto) timed(StageTimes* times, const char* stage, Step&& step) {
  StageTimer timer(times, stage);
  return step();
}

}  // namespace vgeo
