// bench_build.cpp: `vgeo bench build`: the builder's time (DAG only and total), throughput, peak memory
// and DAG quality for each mesh x --subdiv x --threads. Every build runs in a fresh child process
// (this executable's `build --stats`), so peak memory is that build's own; the median of --repeat runs
// is reported (2-core machines are noisy: compare ratios within one run).
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "../common/input_error.h"
#include "../renderer/vulkan_context.h"
#include "bench.h"
#include "commands.h"

extern char** environ;

namespace vgeo {
namespace {

struct BuildBenchArgs {
  std::vector<std::string> inputs;
  std::string output, subdivs = "0,1,2,3", threads = "1,2", groupSizes = "16";
  uint32_t repeat = 3;
  double maxTriangles = 0;  // 0: no limit
  bool quality = true;      // the DAG's cut quality (cut_quality.cpp) from the last build of each mesh and level
  std::string qualitySize = "1280x720", device;
};

std::string cpuName() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

// Runs `vgeo build` in a child process and returns its --stats JSON. Every run writes a new file: the
// last run's output is removed first and the file system synced, outside the timed build. A build that
// replaces its output also pays for dropping the old file in the rename (on ext4 about 6 ms for 19 MB),
// and a build started while the last one's file is still being written back waits for it in its fsync;
// either would make a run's time depend on the run before it.
nlohmann::json buildInChild(const std::string& input, int subdiv, int threads, uint32_t groupSize,
                            const std::string& dir) {
  // This very executable, even if its file was replaced since it started.
  std::string self = "/proc/self/exe";
  std::string out = dir + "/bench.vgeo", stats = dir + "/bench.json";
  std::filesystem::remove(out);
  std::filesystem::remove(stats);
  if (const int folder = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); folder >= 0) {
    ::syncfs(folder);
    ::close(folder);
  }
  std::vector<std::string> args = {self,
                                   "build",
                                   input,
                                   "-o",
                                   out,
                                   "--subdiv",
                                   std::to_string(subdiv),
                                   "--threads",
                                   std::to_string(threads),
                                   "--stats",
                                   stats,
                                   "--group-size",
                                   std::to_string(groupSize),
                                   "-q"};
  std::vector<char*> argv;
  for (auto& s : args) argv.push_back(s.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t quiet;  // its summary lines off stdout; errors still reach stderr
  posix_spawn_file_actions_init(&quiet);
  posix_spawn_file_actions_addopen(&quiet, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid;
  int started = posix_spawn(&pid, self.c_str(), &quiet, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&quiet);
  if (started != 0) throw std::runtime_error("cannot start " + self);
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error(input + ": build --subdiv " + std::to_string(subdiv) + " failed (see above)");
  std::ifstream in(stats);
  return nlohmann::json::parse(in);
}

void runBenchBuild(const BuildBenchArgs& a) {
  std::string dir =
      (std::filesystem::temp_directory_path() / ("vgeo_bench_build_" + std::to_string(getpid()))).string();
  std::filesystem::create_directories(dir);
  nlohmann::ordered_json records = nlohmann::json::array();
  uint32_t qualityWidth = 0, qualityHeight = 0;
  if (!parseSize(a.qualitySize, qualityWidth, qualityHeight)) throw std::runtime_error("--quality-size: expected WxH");
  std::unique_ptr<VulkanContext> vk;  // opened for the first quality measurement
  for (const std::string& input : a.inputs) {
    if (!std::filesystem::exists(input)) throw InputError(input, "no such file");
    double lastLeaves = 0;  // of the last level built, for --max-triangles
    int lastSubdiv = 0;
    for (int subdiv : parseList<int>(a.subdivs)) {
      if (a.maxTriangles > 0 && lastLeaves > 0) {
        // A Catmull-Clark level makes at most 6 triangles of a triangle (3 quads) and 4 of a quad's.
        double predicted = lastLeaves;
        for (int l = lastSubdiv; l < subdiv; l++) predicted *= l == 0 ? 6.0 : 4.0;
        if (predicted > a.maxTriangles) {
          std::fprintf(stderr, "%s: --subdiv %d and deeper skipped: up to %.0f leaf triangles, over --max-triangles\n",
                       input.c_str(), subdiv, predicted);
          break;
        }
      }
      // The thread counts take turns, a build of each per repeat, so that the medians of one and of 16
      // threads come from the same stretch of the machine's time (a host's speed drifts between runs).
      const std::vector<int> threadCounts = parseList<int>(a.threads);
      for (uint32_t groupSize : parseList<uint32_t>(a.groupSizes)) {
        std::vector<std::vector<nlohmann::json>> runsOf(threadCounts.size());
        for (uint32_t i = 0; i < std::max(a.repeat, 1u); i++)
          for (size_t k = 0; k < threadCounts.size(); k++)
            runsOf[k].push_back(buildInChild(input, subdiv, threadCounts[k], groupSize, dir));
        // The cut's cost per pixel and its error against the leaves, of the file the last run wrote (the
        // same bytes for every run and thread count).
        nlohmann::ordered_json quality;
        if (a.quality) {
          if (!vk) vk = std::make_unique<VulkanContext>(ContextOptions{a.device});
          quality = measureCutQuality(*vk, loadRenderScene(dir + "/bench.vgeo"), qualityWidth, qualityHeight, 1.0f);
        }
        for (size_t k = 0; k < threadCounts.size(); k++) {
          const int threads = threadCounts[k];
          const std::vector<nlohmann::json>& runs = runsOf[k];
          std::vector<double> dag, total;
          for (const nlohmann::json& run : runs) {
            dag.push_back(run["build_seconds"].get<double>());
            total.push_back(run["total_seconds"].get<double>());
          }
          const nlohmann::json& s = runs.front();  // the output is identical for every run
          double leaves = s["leaf_triangles"].get<double>();
          uint64_t peak = 0;
          for (const auto& r : runs) peak = std::max(peak, r["peak_rss_bytes"].get<uint64_t>());
          std::vector<double> levelTriangles = s["level_triangles"].get<std::vector<double>>();
          double worstRatio = 0.0;
          for (size_t l = 0; l + 1 < levelTriangles.size(); l++)
            worstRatio = std::max(worstRatio, levelTriangles[l + 1] / levelTriangles[l]);
          nlohmann::ordered_json r;
          r["mesh"] = std::filesystem::path(input).filename().string();
          r["subdiv"] = subdiv;
          r["group_size"] = groupSize;
          r["threads"] = threads;
          r["input_triangles"] = s["input_triangles"];
          r["leaf_triangles"] = s["leaf_triangles"];
          r["dag_seconds"] = median(dag);
          r["total_seconds"] = median(total);
          r["dag_seconds_all"] = dag;
          r["total_seconds_all"] = total;
          r["mtri_per_second"] = leaves / 1e6 / median(dag);
          r["peak_rss_bytes"] = peak;
          r["bytes_per_triangle"] = double(peak) / leaves;
          r["levels"] = s["levels"];
          r["clusters"] = s["clusters"];
          r["root_clusters"] = s["root_clusters"];
          r["avg_leaf_cluster_triangles"] = s["avg_leaf_cluster_triangles"];
          r["avg_cluster_triangles"] = s["avg_cluster_triangles"];
          r["worst_level_ratio"] = worstRatio;
          r["stage_seconds"] = nlohmann::ordered_json::object();  // each step's median over the runs
          for (const auto& [stage, seconds] : s["stage_seconds"].items()) {
            std::vector<double> all;
            for (const auto& run : runs) all.push_back(run["stage_seconds"].value(stage, 0.0));
            r["stage_seconds"][stage] = median(all);
          }
          r["relaxed_groups"] = s["relaxed_groups"];
          r["stuck_groups"] = s["stuck_groups"];
          r["root_triangles"] = levelTriangles.empty() ? 0.0 : levelTriangles.back();
          if (a.quality) r["cut_quality"] = quality;
          r["cpu"] = cpuName();
          r["cores"] = std::thread::hardware_concurrency();
          r["repeat"] = runs.size();
          r["commit"] = VGEO_COMMIT;
          lastLeaves = leaves;
          lastSubdiv = subdiv;
          std::fprintf(
              stderr,
              "%-16s subdiv %d group %u threads %d: %9.0f leaf triangles, DAG %.3f s (%.2f M/s), total %.3f s, %.0f "
              "B/triangle, %d levels, %d roots%s\n",
              r["mesh"].get<std::string>().c_str(), subdiv, groupSize, threads, leaves, median(dag),
              r["mtri_per_second"].get<double>(), median(total), r["bytes_per_triangle"].get<double>(),
              s["levels"].get<int>(), s["root_clusters"].get<int>(),
              a.quality ? (", " + std::to_string(quality["triangles_drawn_per_pixel"].get<double>()) +
                           " triangles a pixel, pixel error " + std::to_string(quality["pixel_error"].get<double>()))
                              .c_str()
                        : "");
          records.push_back(r);
        }
      }
    }
  }
  std::filesystem::remove_all(dir);
  writeJson(a.output, records, 1);
}

}  // namespace

void addBenchBuildCommand(CLI::App& bench, int& exitCode) {
  auto* cmd = bench.add_subcommand(
      "build", "Builder time, throughput, peak memory and DAG quality per mesh, --subdiv and --threads");
  auto a = std::make_shared<BuildBenchArgs>();
  cmd->add_option("inputs", a->inputs, "Meshes (any format `vgeo build` reads)")->required();
  cmd->add_option("-o,--output", a->output, "JSON records")->required();
  cmd->add_option("--subdiv", a->subdivs, "Catmull-Clark levels")->capture_default_str();
  cmd->add_option("--threads", a->threads, "Thread counts")->capture_default_str();
  cmd->add_option("--group-sizes", a->groupSizes, "Clusters a group aims at (`build --group-size`), a record each")
      ->capture_default_str();
  cmd->add_option("--repeat", a->repeat, "Builds per record (median)")->capture_default_str();
  cmd->add_option("--max-triangles", a->maxTriangles,
                  "Stop a mesh's --subdiv levels (in the order given) before one that could make more leaf "
                  "triangles than this (a size sweep: --subdiv 0,1,2,3,4,5,6 --max-triangles 1e8)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("!--no-quality", a->quality, "Skip the cut-quality views (no GPU or lavapipe needed)");
  cmd->add_option("--quality-size", a->qualitySize, "Viewport of the cut-quality views, WxH")->capture_default_str();
  addDeviceOption(cmd, a->device);
  cmd->callback([a, &exitCode] {
    runBenchBuild(*a);
    exitCode = 0;
  });
}

}  // namespace vgeo
