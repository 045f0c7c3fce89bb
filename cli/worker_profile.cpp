// worker_profile.cpp: what the persistent traversal's workers did in one frame, from the per-workgroup
// records of traverse_persistent.comp built with VGEO_PROFILE (layout in shaders/shaderio.h). The cut
// benchmark adds it to its persistent records with --profile-workers: where a frame's time goes (claims,
// polls, the rounds of the iterations that took items, the tail after the last item) when GPU timestamps
// only give the whole dispatch. Times are device-clock ticks (VK_KHR_shader_clock's device scope).
#include <algorithm>
#include <cstdint>

#include "bench.h"

namespace vgeo {

nlohmann::ordered_json summarizeWorkerProfile(const std::vector<uint32_t>& words, uint32_t workgroups) {
  auto at = [&](size_t w) { return uint64_t(words[w]) | uint64_t(words[w + 1]) << 32; };
  uint64_t begin = UINT64_MAX, exit = 0, firstStart = UINT64_MAX, lastEnd = 0, iterations = 0, polls = 0, pollTicks = 0,
           working = 0, recorded = 0, items = 0, tests = 0, busy = 0;
  std::vector<double> claim, take, rounds, whole;
  std::vector<uint64_t> begins;
  struct Taken {
    uint64_t start;
    uint32_t items;
  };
  std::vector<Taken> takenItems;
  for (uint32_t g = 0; g < workgroups; g++) {
    const size_t base = size_t(g) * VGEO_PROFILE_WORKER_WORDS;
    if (base + VGEO_PROFILE_WORKER_WORDS > words.size()) break;
    const uint32_t n = std::min<uint32_t>(words[base], VGEO_PROFILE_ITERATIONS);
    iterations += words[base + 1];
    polls += words[base + 2];
    pollTicks += words[base + 3];
    working += words[base + 1] - words[base + 2];
    recorded += n;
    begin = std::min(begin, at(base + 4));
    begins.push_back(at(base + 4));
    exit = std::max(exit, at(base + 6));
    for (uint32_t i = 0; i < n; i++) {
      const size_t r = base + VGEO_PROFILE_HEADER_WORDS + size_t(i) * VGEO_PROFILE_ITERATION_WORDS;
      const uint64_t start = at(r), claimed = at(r + 2), taken = at(r + 4), end = at(r + 6);
      firstStart = std::min(firstStart, start);
      lastEnd = std::max(lastEnd, end);
      claim.push_back(double(claimed - start));
      take.push_back(double(taken - claimed));
      rounds.push_back(double(end - taken));
      whole.push_back(double(end - start));
      busy += end - start;
      items += words[r + 8];
      takenItems.push_back({start, words[r + 8]});
      tests += uint64_t(words[r + 9]) + words[r + 10];
    }
  }
  nlohmann::ordered_json j;
  j["workgroups"] = workgroups;
  j["iterations"] = iterations;
  j["iterations_with_items"] = working;
  j["iterations_recorded"] = recorded;
  // A worker records its first VGEO_PROFILE_ITERATIONS iterations with items only (lavapipe's few workers
  // run hundreds): then the times of the last item and the tail are of the recorded ones.
  j["truncated"] = recorded < working;
  j["polls"] = polls;
  if (begin == UINT64_MAX) return j;
  j["span_ticks"] = exit - begin;  // first worker's start to last worker's exit
  if (recorded != 0) {
    j["first_item_ticks"] = firstStart - begin;  // from the first worker's start
    j["last_item_end_ticks"] = lastEnd - begin;
    j["tail_ticks"] = exit - lastEnd;  // the last item's end to the last exit
    j["iteration_ticks_median"] = median(whole);
    j["claim_ticks_median"] = median(claim);
    j["take_ticks_median"] = median(take);
    j["rounds_ticks_median"] = median(rounds);
    j["items_per_iteration"] = double(items) / double(recorded);
    j["tests_per_iteration"] = double(tests) / double(recorded);
    // Share of the workers' time spent in iterations that took items.
    j["busy_share"] = double(busy) / (double(workgroups) * double(exit - begin));
    // The frame as a timeline from the first worker's start: workers started, and items taken by
    // iterations that started, in each step. Steps of 1,000 ticks (1 us on NVIDIA and lavapipe), or of as
    // many thousands as keep it within kTimelineSteps (a lavapipe frame spans milliseconds).
    constexpr uint64_t kTimelineSteps = 64;
    const uint64_t span = exit - begin, step = 1000 * std::max<uint64_t>(1, (span / kTimelineSteps + 999) / 1000);
    const size_t steps = size_t(span / step + 1);
    std::vector<uint64_t> started(steps), itemsAt(steps);
    for (uint64_t b : begins) started[std::min<size_t>((b - begin) / step, steps - 1)]++;
    for (const Taken& t : takenItems) itemsAt[std::min<size_t>((t.start - begin) / step, steps - 1)] += t.items;
    j["timeline_step_ticks"] = step;
    j["workers_started"] = started;
    j["items_taken"] = itemsAt;
  }
  if (polls != 0) j["poll_ticks_mean"] = double(pollTicks) / double(polls);
  return j;
}

}  // namespace vgeo
