// test_public_meshes.cpp: every mesh of two public corpora through `vgeo build` and `vgeo check`, as a
// user would run them: CGAL's demo meshes (libcgal-demo's data.tar.gz, 150 files, among them point
// clouds, STL files, shuffled orientations, holes, high genus) and every glTF of Debian's
// assimp-testmodels (valid and broken on purpose). Each file either builds a .vgeo that passes its own
// check and ends with at most one root cluster per connected component (or says why not), or fails
// with exit 1 and one line that names the file, leaving no output behind. Never a crash.
#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "test_util.h"

namespace vgeo {
namespace {

std::vector<std::string> filesUnder(const std::string& dir, const std::vector<std::string>& extensions) {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (std::find(extensions.begin(), extensions.end(), ext) != extensions.end())
      files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

struct SweepCounts {
  int built = 0, refused = 0;
};

// Builds `file` with `--subdiv subdiv` and checks what comes out; failures are reported with the file.
void buildAndCheck(const std::string& file, int subdiv, const std::string& dir, SweepCounts& counts) {
  SCOPED_TRACE(file + " --subdiv " + std::to_string(subdiv));
  const std::string out = dir + "/out.vgeo", stats = dir + "/stats.json";
  std::filesystem::remove(out);
  std::filesystem::remove(stats);
  test::RunResult r = test::runVgeo("build '" + file + "' -o " + out + " --subdiv " + std::to_string(subdiv) +
                                    " --stats " + stats + " -q");
  if (r.exitCode != 0) {
    counts.refused++;
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << "one line: " << r.output;
    EXPECT_EQ(r.output.rfind(file + ": ", 0), 0u) << "names the file: " << r.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << "nothing half-written";
    return;
  }
  counts.built++;
  test::RunResult check = test::runVgeo("check " + out + " --cuts 8");
  EXPECT_EQ(check.exitCode, 0) << check.output;
  std::ifstream in(stats);
  nlohmann::json j = nlohmann::json::parse(in);
  const uint64_t roots = j["root_clusters"], components = j["repair"]["components"];
  if (roots > components) {
    ASSERT_FALSE(j["unreduced"].empty()) << roots << " roots for " << components << " components, and no reason given";
    for (const auto& u : j["unreduced"]) {
      EXPECT_FALSE(u["reason"].get<std::string>().empty());
      const std::string note =
          "note: " + u["mesh"].get<std::string>() + " keeps " + std::to_string(u["root_clusters"].get<uint64_t>());
      EXPECT_NE(r.output.find(note), std::string::npos) << "the summary says so: " << r.output;
    }
  }
}

// Each sweep runs as kShards tests over every kShards-th file, so that a shard stays inside the test
// timeout under the sanitizers (10-15x slower there) with other tests beside it.
constexpr int kShards = 4;

std::vector<std::string> shardOf(const std::vector<std::string>& files, int shard) {
  std::vector<std::string> mine;
  for (size_t i = shard; i < files.size(); i += kShards) mine.push_back(files[i]);
  return mine;
}

// Fails unless at least `percent` of the shard's files built (the rest are refused on purpose: point
// clouds, broken glTFs), so that a sweep that finds no files or refuses everything cannot pass.
void expectBuilt(const SweepCounts& counts, size_t files, int percent, const char* what) {
  std::printf("%s: %d built, %d refused\n", what, counts.built, counts.refused);
  EXPECT_GT(files, 0u);
  EXPECT_GE(counts.built * 100, int(files) * percent) << counts.built << " of " << files << " built";
}

class PublicMeshes : public ::testing::TestWithParam<int> {};

TEST_P(PublicMeshes, EveryCgalDemoMeshBuildsAndChecksOrIsRefusedClearly) {
  const std::string dir = test::tempDir();
  SweepCounts counts;
  const std::vector<std::string> files =
      shardOf(filesUnder(std::string(VGEO_TEST_DATA) + "/data", {".off", ".obj", ".ply", ".stl"}), GetParam());
  for (const std::string& file : files) buildAndCheck(file, 0, dir, counts);
  expectBuilt(counts, files.size(), 75, "CGAL demo meshes");
}

TEST_P(PublicMeshes, CgalDemoMeshesSubdividedOnceBuildAndCheck) {
  // The cages as Catmull-Clark inputs (patches, limit positions); the largest few are left to the DAG tests.
  const std::string dir = test::tempDir();
  SweepCounts counts;
  std::vector<std::string> cages;
  for (const std::string& file : filesUnder(std::string(VGEO_TEST_DATA) + "/data/meshes", {".off", ".obj", ".ply"}))
    if (std::filesystem::file_size(file) < 600'000) cages.push_back(file);
  const std::vector<std::string> files = shardOf(cages, GetParam());
  for (const std::string& file : files) buildAndCheck(file, 1, dir, counts);
  expectBuilt(counts, files.size(), 85, "CGAL demo meshes, --subdiv 1");
}

TEST_P(PublicMeshes, EveryAssimpGltfBuildsAndChecksOrIsRefusedClearly) {
  const std::string dir = test::tempDir();
  SweepCounts counts;
  const std::vector<std::string> files =
      shardOf(filesUnder("/usr/share/assimp/models/glTF2", {".gltf", ".glb"}), GetParam());
  for (const std::string& file : files)
    for (int subdiv : {0, 1}) buildAndCheck(file, subdiv, dir, counts);
  expectBuilt(counts, 2 * files.size(), 40, "assimp glTF models (subdiv 0 and 1)");
}

INSTANTIATE_TEST_SUITE_P(Shard, PublicMeshes, ::testing::Range(0, kShards));

}  // namespace
}  // namespace vgeo
