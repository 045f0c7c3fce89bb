// test_bench.cpp: `vgeo bench cut` writes one record per (layout, size, camera, tau, mode), and every mode
// agrees on the clusters drawn; `bench frame` and `bench build` write their records.
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "test_util.h"

namespace vgeo {
namespace {

// Runs `vgeo bench ARGS -o OUTPUT` and returns the records it wrote (none, and a failure, if it failed).
nlohmann::json benchRecords(const std::string& args, const std::string& output) {
  test::RunResult r = test::runVgeo("bench " + args + " -o " + output);
  EXPECT_EQ(r.exitCode, 0) << r.output;
  if (r.exitCode != 0) return nlohmann::json::array();
  std::ifstream in(output);
  return nlohmann::json::parse(in);
}

TEST(BenchCut, WritesRecordsOnWhichAllModesAgree) {
  std::string dir = test::tempDir();
  writeVgeo(test::build(test::asset("horned_cube.obj"), 2), dir + "/h.vgeo");
  nlohmann::json records =
      benchRecords("cut " + dir + "/h.vgeo --sizes 1,9 --taus 1,4 --frames 1 --size 160x120", dir + "/cut.json");
  EXPECT_EQ(records.size(), 2u * 2u * 8u * 2u * 4u);  // layouts x sizes x cameras x taus x modes
  std::map<std::string, std::vector<uint64_t>> drawn;
  for (const auto& rec : records) {
    for (const char* key :
         {"layout", "instances", "camera", "tau", "mode", "traversal_ms", "visible_clusters", "device", "commit"})
      EXPECT_TRUE(rec.contains(key)) << key;
    if (rec["mode"] != "cpu") {
      // lavapipe culls in a pass of its own (the persistent traversal culls itself on GPUs only)
      ASSERT_TRUE(rec.contains("instance_culling"));
      if (rec["mode"] != "persistent") {
        EXPECT_EQ(rec["instance_culling"], "pass");
      }
    }
    if (rec["mode"] != "cpu") {
      // The cut alone by default, and what it costs per pixel it covers: every drawn triangle was listed.
      EXPECT_EQ(rec["occlusion_setting"], "off");
      EXPECT_EQ(rec["two_pass_frames"], 0);
      if (rec["pixels_covered"].get<uint64_t>() > 0) {
        EXPECT_GT(rec["triangles_listed_per_pixel"].get<double>(), 0.0);
        EXPECT_LE(rec["triangles_drawn_per_pixel"].get<double>(), rec["triangles_listed_per_pixel"].get<double>());
      }
    }
    std::string group = rec["layout"].get<std::string>() + std::to_string(rec["instances"].get<int>()) +
                        rec["camera"].get<std::string>() + std::to_string(rec["tau"].get<double>());
    drawn[group].push_back(rec["visible_clusters"].get<uint64_t>());
  }
  for (const auto& [group, counts] : drawn)
    for (uint64_t c : counts) EXPECT_EQ(c, counts[0]) << group;
}

TEST(BenchFrame, SplitsTheFrameWithAndWithoutTriangleCullingAndPatches) {
  std::string dir = test::tempDir();
  writeVgeo(test::build(test::asset("horned_cube.obj"), 2), dir + "/h.vgeo");
  nlohmann::json records = benchRecords(
      "frame " + dir + "/h.vgeo --grids 1,3 --sizes 160x120 --cameras corner,surface --frames 1 --occlusion off",
      dir + "/frame.json");
  // grids x cameras x (each of --rasters auto,hardware: patches, triangle culling only; then neither)
  constexpr size_t kVariants = 5;
  ASSERT_EQ(records.size(), 2u * 2u * kVariants);
  uint64_t softwareTriangles = 0;
  for (size_t i = 0; i < records.size(); i += kVariants) {
    const auto &patches = records[i], &on = records[i + 1], &hardwarePatches = records[i + 2],
               &hardwareOn = records[i + 3], &off = records[i + 4];
    for (const char* key : {"instance_culling", "instance_cull_ms", "traversal_ms", "triangle_cull_ms", "raster_ms",
                            "resolve_ms", "draw_ms", "frame_ms", "pixels_covered", "patches_drawn", "patch_triangles",
                            "patch_pixels", "software_triangles", "device", "commit"})
      EXPECT_TRUE(patches.contains(key)) << key;
    EXPECT_TRUE(patches["patches"].get<bool>() && patches["triangle_cull"].get<bool>());
    EXPECT_TRUE(on["triangle_cull"].get<bool>() && !on["patches"].get<bool>());
    EXPECT_FALSE(off["triangle_cull"].get<bool>() || off["patches"].get<bool>());
    EXPECT_EQ(patches["raster"], "auto");
    EXPECT_EQ(hardwareOn["raster"], "hardware");
    EXPECT_EQ(on["visible_clusters"], off["visible_clusters"]);
    EXPECT_EQ(patches["visible_clusters"], on["visible_clusters"]);
    EXPECT_EQ(off["triangles_drawn"], off["triangles"]);
    EXPECT_LT(on["triangles_drawn"].get<uint64_t>(), on["triangles"].get<uint64_t>());
    // The rasterizer changes where a triangle goes, not which are drawn, nor how many pixels they cover.
    EXPECT_EQ(on["triangles_drawn"], hardwareOn["triangles_drawn"]);
    EXPECT_EQ(patches["patches_drawn"], hardwarePatches["patches_drawn"]);
    EXPECT_EQ(hardwareOn["software_triangles"].get<uint64_t>(), 0u);
    EXPECT_LE(on["software_triangles"].get<uint64_t>(), on["triangles_drawn"].get<uint64_t>());
    softwareTriangles += on["software_triangles"].get<uint64_t>();
    EXPECT_NEAR(double(on["pixels_covered"].get<uint64_t>()), double(hardwareOn["pixels_covered"].get<uint64_t>()),
                0.002 * double(hardwareOn["pixels_covered"].get<uint64_t>()) + 2.0);
    EXPECT_GT(on["pixels_covered"].get<uint64_t>(), 0u);
    EXPECT_EQ(on["patches_drawn"].get<uint64_t>(), 0u);
    if (patches["camera"] == "surface") {
      EXPECT_GT(patches["patches_drawn"].get<uint64_t>(), 0u);
      EXPECT_GT(patches["patch_pixels"].get<uint64_t>(), 0u);
    }
  }
  EXPECT_GT(softwareTriangles, 0u);
  EXPECT_EQ(records[2 * kVariants]["instances"].get<int>(), 9);
}

TEST(BenchFrame, ForestWithAndWithoutOcclusionCulling) {
  std::string dir = test::tempDir();
  writeVgeo(test::build(test::asset("horned_cube.obj"), 2), dir + "/h.vgeo");
  nlohmann::json records = benchRecords("frame " + dir +
                                            "/h.vgeo --layout forest --grids 8 --sizes 160x120 --cameras "
                                            "ground,flythrough --path-frames 4 --rasters auto --frames 2",
                                        dir + "/forest.json");
  // cameras x (patches, triangle culling only, neither) x occlusion on, off
  ASSERT_EQ(records.size(), 2u * 3u * 2u);
  for (size_t i = 0; i < records.size(); i += 2) {
    const auto &on = records[i], &off = records[i + 1];
    EXPECT_EQ(on["instances"].get<int>(), 64);
    EXPECT_TRUE(on["occlusion"].get<bool>());
    EXPECT_FALSE(off["occlusion"].get<bool>());
    EXPECT_EQ(on["occlusion_setting"], "on");
    EXPECT_EQ(off["occlusion_setting"], "off");
    for (const char* key : {"pyramid_ms", "frame_max_ms", "frame_mean_ms", "clusters_median", "early_clusters",
                            "occluded_instances", "occluded_nodes", "occluded_clusters"})
      EXPECT_TRUE(on.contains(key)) << key;
    EXPECT_EQ(on["pixels_covered"], off["pixels_covered"]);  // the same picture
    EXPECT_LE(on["visible_clusters"].get<uint64_t>(), off["visible_clusters"].get<uint64_t>());
    EXPECT_EQ(on["frames"].get<int>(), on["camera"] == "flythrough" ? 4 : 2);
    EXPECT_EQ(off["pyramid_ms"].get<double>(), 0.0);
  }
}

TEST(BenchBuild, OneRecordPerMeshSubdivAndThreads) {
  std::string dir = test::tempDir();
  nlohmann::json records = benchRecords(
      "build " + test::asset("horned_cube.obj") + " --subdiv 0,1 --threads 1,2 --repeat 2", dir + "/build.json");
  ASSERT_EQ(records.size(), 4u);
  for (size_t i = 0; i < records.size(); i++) {  // by level, then by thread count, as given
    EXPECT_EQ(records[i]["subdiv"].get<int>(), int(i / 2));
    EXPECT_EQ(records[i]["threads"].get<int>(), int(i % 2) + 1);
  }
  for (const auto& rec : records) {
    EXPECT_EQ(rec["dag_seconds_all"].size(), 2u);  // every run's, of the turns the thread counts took
    EXPECT_EQ(rec["total_seconds_all"].size(), 2u);
    for (const char* key : {"dag_seconds", "total_seconds", "mtri_per_second", "peak_rss_bytes", "levels",
                            "root_clusters", "relaxed_groups"})
      EXPECT_TRUE(rec.contains(key)) << key;
    EXPECT_GT(rec["peak_rss_bytes"].get<uint64_t>(), 0u);
    EXPECT_LE(rec["dag_seconds"].get<double>(), rec["total_seconds"].get<double>());
    // Each step's seconds: every step of the run, none more than the whole. A step's median and the
    // total's may come from different runs (of two, the median is the slower), so the steps together
    // are held to the runs' totals together: each run's steps fit in its own total.
    double steps = 0.0, totals = 0.0;
    for (const char* stage : {"load", "repair", "leaf clusters", "grouping", "simplify and split", "layout", "write"}) {
      ASSERT_TRUE(rec["stage_seconds"].contains(stage)) << stage;
      EXPECT_LE(rec["stage_seconds"][stage].get<double>(), rec["total_seconds"].get<double>()) << stage;
      steps += rec["stage_seconds"][stage].get<double>();
    }
    for (const auto& total : rec["total_seconds_all"]) totals += total.get<double>();
    EXPECT_LE(steps, totals);
    // The cut's quality from five views: a root of at most 8 triangles for a far instance, some triangles
    // a pixel, and at tau 1 a picture within a few per cent of the leaves' (tau 0.01).
    EXPECT_LE(rec["root_triangles"].get<double>(), 8.0);
    const auto& q = rec["cut_quality"];
    ASSERT_EQ(q["views"].size(), 5u);
    EXPECT_GT(q["triangles_drawn_per_pixel"].get<double>(), 0.0);
    EXPECT_LE(q["triangles_drawn_per_pixel"].get<double>(), q["triangles_listed_per_pixel"].get<double>());
    EXPECT_GE(q["pixel_error"].get<double>(), q["coverage_error"].get<double>());
    EXPECT_LT(q["pixel_error"].get<double>(), 0.05);
    for (const auto& v : q["views"]) EXPECT_GT(v["covered_pixels"].get<uint64_t>(), 0u) << v["view"];
  }
  // A level-0 DAG is exact at every cut of its leaves' own level: the picture of the finest views equals
  // the leaves' where the cut is the leaves (the framing views of 684 triangles at 1280x720).
  EXPECT_EQ(records[0]["cut_quality"]["views"][0]["pixel_error"].get<double>(), 0.0);
  // Every face of a level-1 cage is a quad: 684 triangles (342 quads) -> 4 x 342 quads = 2,736 triangles.
  EXPECT_EQ(records[2]["leaf_triangles"].get<int>(), 2736);
  EXPECT_EQ(records[0]["clusters"], records[1]["clusters"]);  // the DAG does not depend on the thread count
  // A size sweep: levels stop before one that could pass --max-triangles (684, 2,736, 10,944 leaf
  // triangles; the next could be 43,776).
  nlohmann::json sweep = benchRecords(
      "build " + test::asset("horned_cube.obj") + " --subdiv 0,1,2,3,4 --threads 1 --repeat 1 --max-triangles 20000",
      dir + "/sweep.json");
  ASSERT_EQ(sweep.size(), 3u);
  EXPECT_EQ(sweep[2]["leaf_triangles"].get<int>(), 10944);
  test::RunResult bad = test::runVgeo("bench build " + dir + "/missing.obj -o " + dir + "/b.json");
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_NE(bad.output.find("missing.obj: "), std::string::npos) << bad.output;
}

}  // namespace
}  // namespace vgeo
