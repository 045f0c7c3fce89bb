// test_bench.cpp: `vgeo bench cut` writes one record per (layout, size, camera, tau, mode), and every mode
// agrees on the clusters drawn.
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "test_util.h"

namespace vgeo {
namespace {

TEST(BenchCut, WritesRecordsOnWhichAllModesAgree) {
  std::string dir = test::tempDir();
  writeVgeo(test::build(test::asset("horned_cube.obj"), 2), dir + "/h.vgeo");
  test::RunResult r = test::runVgeo("bench cut " + dir + "/h.vgeo -o " + dir + "/cut.json --sizes 1,9 --taus 1,4 --frames 1 --size 160x120");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream in(dir + "/cut.json");
  nlohmann::json records = nlohmann::json::parse(in);
  EXPECT_EQ(records.size(), 2u * 2u * 5u * 2u * 4u);  // layouts x sizes x cameras x taus x modes
  std::map<std::string, std::vector<uint64_t>> drawn;
  for (const auto& rec : records) {
    for (const char* key : {"layout", "instances", "camera", "tau", "mode", "traversal_ms", "visible_clusters", "device", "commit"})
      EXPECT_TRUE(rec.contains(key)) << key;
    std::string group = rec["layout"].get<std::string>() + std::to_string(rec["instances"].get<int>()) + rec["camera"].get<std::string>() +
                        std::to_string(rec["tau"].get<double>());
    drawn[group].push_back(rec["visible_clusters"].get<uint64_t>());
  }
  for (const auto& [group, counts] : drawn)
    for (uint64_t c : counts) EXPECT_EQ(c, counts[0]) << group;
}

}  // namespace
}  // namespace vgeo
