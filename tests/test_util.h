// test_util.h: shared helpers of the tests: data paths, running the vgeo binary, building in memory.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "../builder/build_scene.h"
#include "../reference/cut.h"

namespace vgeo::test {

inline std::string cgalMesh(const std::string& name) { return std::string(VGEO_TEST_DATA) + "/data/meshes/" + name; }
inline std::string assimpModel(const std::string& path) { return "/usr/share/assimp/models/glTF2/" + path; }
inline std::string asset(const std::string& name) { return std::string(VGEO_SOURCE_DIR) + "/assets/" + name; }

// A fresh directory for one test's files.
inline std::string tempDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path dir = std::filesystem::temp_directory_path() /
                              ("vgeo_test_" + std::string(info->test_suite_name()) + "_" + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

struct RunResult {
  int exitCode;
  std::string output;  // stdout and stderr together
};
// Runs a shell command line, stdout and stderr together.
inline RunResult runShell(const std::string& commandLine) {
  std::string command = "{ " + commandLine + "; } 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  RunResult r{-1, {}};
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) r.output.append(buffer, n);
  int status = pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}
// Runs the vgeo binary with `args` (a shell-quoted string).
inline RunResult runVgeo(const std::string& args) { return runShell(std::string(VGEO_BINARY) + " " + args); }

inline VgeoData build(const std::string& path, int subdiv, int threads = 2, SceneBuildStats* statsOut = nullptr) {
  SceneBuildOptions options;
  options.subdivisionLevels = subdiv;
  options.threads = threads;
  SceneBuildStats stats;
  VgeoData data = buildScene(path, options, stats);
  if (statsOut) *statsOut = stats;
  return data;
}

// The whole of a file.
inline std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Writes text to a file in `dir` and returns its path.
inline std::string writeFile(const std::string& dir, const std::string& name, const std::string& text) {
  std::string path = dir + "/" + name;
  FILE* f = std::fopen(path.c_str(), "wb");
  std::fwrite(text.data(), 1, text.size(), f);
  std::fclose(f);
  return path;
}

}  // namespace vgeo::test
