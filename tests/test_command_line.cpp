// test_command_line.cpp: what `vgeo` says to a bad command line, a bad scene file and a failed write:
// one line, the documented exit code (options.h: 1 file, 2 usage, 5 machine limits), no output left
// behind, and for bad values no work done first.
#include <chrono>
#include <filesystem>

#include <unistd.h>

#include "test_util.h"

namespace vgeo {
namespace {

class CommandLine : public ::testing::Test {
 protected:
  // A folder of this process's own: ctest runs each test as a process, several at once, and one test's
  // out.png must not be another's.
  static void SetUpTestSuite() {
    dir = new std::string(std::filesystem::temp_directory_path() /
                          ("vgeo_command_line_tests_" + std::to_string(::getpid())));
    std::filesystem::create_directories(*dir);
    writeVgeo(test::build(test::cgalMesh("cow.off"), 0), *dir + "/cow.vgeo");
  }
  static void TearDownTestSuite() {
    std::filesystem::remove_all(*dir);
    delete dir;
  }

  // Runs `args`, expects exit `code` with one line on the output containing `expected`, and no PNG.
  static void expectOneLine(const std::string& args, int code, const std::string& expected) {
    SCOPED_TRACE(args);
    std::filesystem::remove(*dir + "/out.png");
    auto start = std::chrono::steady_clock::now();
    test::RunResult r = test::runVgeo(args);
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(r.exitCode, code) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << "expected '" << expected << "' in: " << r.output;
    EXPECT_FALSE(std::filesystem::exists(*dir + "/out.png"));
    if (code == 2) {
      EXPECT_LT(seconds, 5.0) << "a usage error is found before any work";
    }
  }
  static std::string render(const std::string& options) {
    return "render " + *dir + "/cow.vgeo -o " + *dir + "/out.png " + options;
  }

  static std::string* dir;
};
std::string* CommandLine::dir = nullptr;

TEST_F(CommandLine, BadValuesAreUsageErrorsBeforeAnyWork) {
  expectOneLine(render("--fov 0"), 2, "--fov");
  expectOneLine(render("--fov 180"), 2, "--fov");
  expectOneLine(render("--fov -10"), 2, "--fov");
  expectOneLine(render("--camera nan,0,0,0,0,0"), 2, "--camera: every number must be finite");
  expectOneLine(render("--camera 1,2,3,1,2,3"), 2, "the eye and the target are the same point");
  expectOneLine(render("--camera 1,2,3"), 2, "expected six numbers");
  expectOneLine(render("--tau inf"), 2, "--tau");
  expectOneLine(render("--tau 0"), 2, "--tau");
  expectOneLine(render("--tau nan"), 2, "--tau");
  expectOneLine(render("--mode bogus"), 2, "--mode");
  expectOneLine(render("--traversal bogus"), 2, "--traversal");
  expectOneLine(render("--raster bogus"), 2, "--raster");
  expectOneLine(render("--raster software --no-triangle-cull"), 2, "needs triangle culling");
  expectOneLine(render("--size 0x10"), 2, "--size");
  expectOneLine(render("--frames 0"), 2, "--frames");
  expectOneLine("render " + *dir + "/cow.vgeo -o " + *dir + "/missing/out.png", 2, "does not exist");
  expectOneLine("render " + *dir + "/cow.vgeo -o " + *dir + "/out.jpg", 2, "written as .png");
  expectOneLine("render " + *dir + "/cow.vgeo -o " + *dir + "/out.png --stats " + *dir + "/missing/s.json", 2,
                "--stats");
  expectOneLine("build " + test::cgalMesh("cow.off") + " -o " + *dir + "/c.obj", 2, "written as .vgeo");
  expectOneLine("build " + test::cgalMesh("cow.off") + " -o " + *dir + "/c.vgeo --subdiv 1 --crease-angle 30", 2,
                "--crease-angle");
  expectOneLine("build " + test::cgalMesh("cow.off") + " -o " + *dir + "/c.vgeo --crease-angle 200", 2,
                "--crease-angle");
  expectOneLine("check " + *dir + "/cow.vgeo --cuts -1", 2, "--cuts");
  expectOneLine("render", 2, "input is required");
  // The input itself is never overwritten.
  std::filesystem::copy_file(*dir + "/cow.vgeo", *dir + "/same.vgeo",
                             std::filesystem::copy_options::overwrite_existing);
  expectOneLine("build " + *dir + "/same.vgeo -o " + *dir + "/same.vgeo", 2,
                "is an input or another output of this command");
  // A bad file is the file's fault (exit 1, its name first), not the command line's.
  expectOneLine("render " + *dir + "/nothing.vgeo -o " + *dir + "/out.png", 1, *dir + "/nothing.vgeo: ");
}

TEST_F(CommandLine, AScenePastTheDevicesMemoryIsRefusedBeforeAnyUpload) {
  // 40,000 cows: their instance records alone take 2.4 MiB. Planned for a device of 1 MiB, the scene is
  // refused with one line naming the file, what it needs and what the device has; with 64 MiB it renders.
  expectOneLine(render("--grid 200 --device-memory 1"), 5, *dir + "/cow.vgeo: scene too large for this device");
  expectOneLine(render("--grid 200 --device-memory 1"), 5, "the device's memory is 1 MiB");
  test::RunResult r = test::runVgeo(render("--grid 200 --device-memory 64 --size 64x48"));
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(*dir + "/out.png"));
}

TEST_F(CommandLine, OutputsAreNeverLinksOrDevicesAndInterruptionsLeaveNothing) {
  // An existing output that is not a regular file would be replaced by the atomic rename: refused.
  std::filesystem::remove(*dir + "/link.png");
  std::filesystem::create_symlink(*dir + "/cow.vgeo", *dir + "/link.png");
  expectOneLine("render " + *dir + "/cow.vgeo -o " + *dir + "/link.png", 2, "not a regular file");
  std::filesystem::remove(*dir + "/fifo.vgeo");
  test::runShell("mkfifo " + *dir + "/fifo.vgeo");
  expectOneLine("build " + test::cgalMesh("cow.off") + " -o " + *dir + "/fifo.vgeo", 2, "not a regular file");
  EXPECT_TRUE(std::filesystem::is_symlink(*dir + "/link.png"));
  // SIGINT and SIGTERM at any moment of a build: the output is absent or whole, never a temporary file.
  const std::string out = *dir + "/interrupted.vgeo";
  for (int i = 0; i < 12; i++) {
    std::filesystem::remove(out);
    const std::string sig = i % 2 ? "TERM" : "INT";
    test::runShell(std::string(VGEO_BINARY) + " build " + test::cgalMesh("armadillo.off") + " -q -o " + out +
                   " & pid=$!; sleep " + std::to_string(0.04 * i) + "; kill -" + sig + " $pid; wait $pid");
    for (const auto& entry : std::filesystem::directory_iterator(*dir))
      EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos)
          << "after SIG" << sig << " at " << 0.04 * i << " s: " << entry.path();
    if (std::filesystem::exists(out)) {
      EXPECT_EQ(test::runVgeo("check " + out + " --cuts 2").exitCode, 0);
    }
  }
  // Two builds of one output at once leave one whole file.
  std::filesystem::remove(out);
  test::runShell(std::string(VGEO_BINARY) + " build " + test::cgalMesh("cow.off") + " -q -o " + out + " & " +
                 std::string(VGEO_BINARY) + " build " + test::cgalMesh("cow.off") + " -q -o " + out + " & wait");
  EXPECT_EQ(test::runVgeo("check " + out).exitCode, 0);
}

TEST_F(CommandLine, VersionAndHelpShowWhatTheyShould) {
  test::RunResult v = test::runVgeo("--version");
  EXPECT_EQ(v.exitCode, 0);
  EXPECT_EQ(v.output.rfind("vgeo ", 0), 0u) << v.output;
  test::RunResult h = test::runVgeo("render --help");
  EXPECT_EQ(h.exitCode, 0);
  EXPECT_NE(h.output.find("=1280x720"), std::string::npos) << "defaults in the help: " << h.output;
  EXPECT_NE(h.output.find("Exit codes"), std::string::npos) << h.output;
}

TEST_F(CommandLine, SceneFilesAreReadStrictly) {
  struct SceneCase {
    std::string json, expected;
  };
  const std::vector<SceneCase> cases = {
      {R"({"geometries": ["cow.vgeo"], "instances": [{"geometry": 0, "tranlsation": [1, 0, 0]}]})",
       "unknown key 'tranlsation'"},
      {R"({"geometries": ["cow.vgeo"], "instances": [{"geometry": 0.5}]})", "'geometry' must be an index"},
      {R"({"geometries": ["cow.vgeo"], "instances": [{"geometry": -1}]})", "got -1"},
      {R"({"geometries": ["cow.vgeo"], "instances": [{"geometry": 1}]})", "got 1"},
      {R"({"geometries": ["cow.vgeo"], "instances": [{"geometry": 0, "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1], "scale": 2}]})",
       "'matrix' and"},
      {R"({"geometries": ["cow.vgeo"], "instances": [{"geometry": 0, "rotation": [0, 0, 0, 0]}]})", "zero quaternion"},
      {R"({"geometries": ["cow.vgeo"], "instances": [{"geometry": 0, "scale": [1, 0, 1]}]})", "degenerate transform"},
      {R"({"geometries": ["cow.vgeo"], "instances": [{"geometry": 0, "matrix": [1,0,0,1, 0,1,0,0, 0,0,1,0, 0,0,0,1]}]})",
       "no projection"},
      {R"({"geometries": ["cow.vgeo"], "extra": true})", "unknown key 'extra'"},
      {R"({"geometries": ["/etc/passwd"]})", "must be a path relative to the scene file"},
      {R"({"geometries": ["../outside.vgeo"]})", "leaves the scene file's folder"},
      {R"({"geometries": ["."]})", "is not a file"},
      {R"({"geometries": []})", "non-empty array"},
      {R"({"geometries": ["cow.vgeo"], "instances": [{"geometry": 0, "translation": [1, 2]}]})",
       "'translation' needs 3 numbers"},
  };
  for (const SceneCase& c : cases) {
    const std::string scene = test::writeFile(*dir, "scene.json", c.json);
    expectOneLine("render " + scene + " -o " + *dir + "/out.png", 1, scene + ": ");
    expectOneLine("render " + scene + " -o " + *dir + "/out.png", 1, c.expected);
  }
  // A valid scene renders.
  const std::string good =
      test::writeFile(*dir, "good.json",
                      R"({"geometries": [{"path": "cow.vgeo"}], "instances": [{"geometry": 0, "scale": [-1, 1, 1]}]})");
  test::RunResult r = test::runVgeo("render " + good + " -o " + *dir + "/good.png --size 64x48");
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

TEST_F(CommandLine, FailedWritesLeaveNothingAndSaySo) {
  // A file size limit of 8 KiB (the shell's ulimit -f counts 1 KiB blocks; SIGXFSZ ignored so that the
  // write fails with EFBIG), as a full disk would: the PNG, the stats and the .vgeo fail with one line
  // and exit 1, and neither they nor a temporary file are left.
  auto limited = [](const std::string& args, int kib) {
    return test::runShell("trap '' XFSZ; ulimit -f " + std::to_string(kib) + "; " + std::string(VGEO_BINARY) + " " +
                          args);
  };
  struct WriteCase {
    std::string args;
    int kib;
  };
  for (const WriteCase& c :
       {WriteCase{render("--size 640x480"), 8},
        WriteCase{"render " + *dir + "/cow.vgeo -o " + *dir + "/small.png --size 16x12 --stats " + *dir + "/big.json",
                  1},
        WriteCase{"build " + test::cgalMesh("armadillo.off") + " -o " + *dir + "/big.vgeo -q", 64}}) {
    SCOPED_TRACE(c.args);
    test::RunResult r = limited(c.args, c.kib);
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_NE(r.output.find("write failed"), std::string::npos) << r.output;
  }
  for (const auto& entry : std::filesystem::directory_iterator(*dir)) {
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << "temporary file left: " << entry.path();
    EXPECT_NE(entry.path().filename(), "big.vgeo");
    EXPECT_NE(entry.path().filename(), "big.json");
  }
  EXPECT_FALSE(std::filesystem::exists(*dir + "/out.png"));
}

}  // namespace
}  // namespace vgeo
