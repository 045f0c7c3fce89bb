// build_command.cpp: `vgeo build IN -o OUT.vgeo`, the builder's command line.
#include <sys/resource.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <thread>

#include "../builder/build_scene.h"
#include "commands.h"
#include "options.h"
#include "progress.h"

namespace vgeo {

uint64_t peakRssBytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return uint64_t(usage.ru_maxrss) * 1024;
}

void addBuildCommand(CLI::App& app, int& exitCode) {
  auto* cmd =
      app.add_subcommand("build", "Build a cluster LOD DAG (.vgeo) from a mesh file (.obj .off .ply .gltf .glb)");
  struct Args {
    std::string input, output, stats;
    int subdiv = 0;
    uint32_t groupSize = 16;
    float creaseAngle = 180.0f;
    int threads = int(std::max(1u, std::thread::hardware_concurrency()));
    bool quiet = false;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("input", args->input, "Mesh file")->required();
  cmd->add_option("-o,--output", args->output, "Output .vgeo file")->required();
  cmd->add_option("--subdiv", args->subdiv, "Catmull-Clark levels applied to the input cage")
      ->capture_default_str()
      ->check(CLI::Range(0, 16));
  cmd->add_option("--crease-angle", args->creaseAngle,
                  "Inputs without normals: a hard edge where faces meet at more than DEG degrees (180: smooth; glTF "
                  "without normals is flat)")
      ->capture_default_str()
      ->check(CLI::Range(0.0f, 180.0f));
  cmd->add_option("--group-size", args->groupSize,
                  "Clusters a group aims at, simplified together (a trade of triangles drawn against build time: "
                  "bench/cut-quality.md)")
      ->capture_default_str()
      ->check(CLI::Range(2, 64));
  cmd->add_option("--threads", args->threads, "Worker threads (the output does not depend on it; default: the cores)")
      ->check(CLI::Range(1, 256));
  cmd->add_option("--stats", args->stats, "Write build statistics as JSON to this file");
  cmd->add_flag("-q,--quiet", args->quiet, "No progress bar");
  cmd->callback([args, &exitCode] {
    checkOutputPath("--output", args->output, {args->input}, ".vgeo");
    if (!args->stats.empty()) checkOutputPath("--stats", args->stats, {args->input, args->output});
    if (args->creaseAngle < 180.0f && args->subdiv > 0)
      throw UsageError("--crease-angle",
                       "applies to --subdiv 0: a subdivided cage is shaded with its limit surface's normals");
    auto start = std::chrono::steady_clock::now();
    ProgressBar bar(args->quiet);
    SceneBuildOptions options;
    options.subdivisionLevels = args->subdiv;
    options.threads = args->threads;
    options.groupSize = args->groupSize;
    options.creaseAngleDegrees = args->creaseAngle;
    options.progress = [&](double f, const char* stage) { bar.update(f, stage); };
    SceneBuildStats s;
    VgeoFileSink file(args->output, args->threads);
    buildScene(args->input, options, s, file);
    StageTimer writing(&s.stages, "write");
    file.commit();
    writing.stop();
    bar.finish();
    double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    uint64_t rss = peakRssBytes();
    // The stats before the summary: a failed write is then the one line printed.
    if (!args->stats.empty()) {
      nlohmann::ordered_json j;
      j["input"] = args->input;
      j["subdiv"] = args->subdiv;
      j["input_triangles"] = s.inputTriangles;
      j["leaf_triangles"] = s.leafTriangles;
      j["levels"] = s.levels;
      j["clusters"] = s.clusters;
      j["level_clusters"] = s.levelClusters;
      j["level_triangles"] = s.levelTriangles;
      j["root_clusters"] = s.rootClusters;
      j["avg_leaf_cluster_triangles"] = s.leafClusters ? double(s.levelTriangles[0]) / double(s.leafClusters) : 0.0;
      j["avg_cluster_triangles"] = s.clusters ? double(s.clusterTriangles) / double(s.clusters) : 0.0;
      j["relaxed_groups"] = s.relaxedGroups;
      j["stuck_groups"] = s.stuckGroups;
      j["unreduced"] = nlohmann::ordered_json::array();
      for (const UnreducedMesh& u : s.unreduced)
        j["unreduced"].push_back({{"mesh", u.mesh},
                                  {"root_clusters", u.rootClusters},
                                  {"root_triangles", u.roots.triangles},
                                  {"root_components", u.roots.components},
                                  {"genus", u.roots.genus},
                                  {"boundary_loops", u.roots.boundaryLoops},
                                  {"reason", u.reason}});
      j["geometries"] = s.geometries;
      j["instances"] = s.instances;
      j["zero_scale_instances"] = s.zeroScaleInstances;  // left out: they show nothing
      j["repair"] = {{"welded_vertices", s.repair.weldedVertices},
                     {"degenerate_faces", s.repair.degenerateFaces},
                     {"duplicate_faces", s.repair.duplicateFaces},
                     {"non_manifold_edges", s.repair.nonManifoldEdges},
                     {"split_vertices", s.repair.splitVertices},
                     {"boundary_edges", s.repair.boundaryEdges},
                     {"flipped_faces", s.repair.flippedFaces},
                     {"components", s.repair.components},
                     {"dissolved_vertices", s.repair.dissolvedVertices},
                     {"non_orientable_components", s.repair.nonOrientableComponents}};
      j["load_seconds"] = s.loadSeconds;
      j["subdivide_seconds"] = s.subdivideSeconds;
      j["build_seconds"] = s.buildSeconds;
      j["total_seconds"] = total;
      j["peak_rss_bytes"] = rss;
      j["stage_seconds"] = nlohmann::ordered_json::object();
      for (const auto& [stage, seconds] : s.stages.seconds) j["stage_seconds"][stage] = seconds;
      j["threads"] = args->threads;
      writeJson(args->stats, j, 2);
    }
    std::printf(
        "built %s: %u geometr%s, %u instance%s; %llu input -> %llu leaf triangles; %llu clusters (%.1f triangles per "
        "leaf cluster), "
        "%u levels, %llu root cluster%s, %llu relaxed groups\n",
        args->output.c_str(), s.geometries, s.geometries == 1 ? "y" : "ies", s.instances, s.instances == 1 ? "" : "s",
        (unsigned long long)s.inputTriangles, (unsigned long long)s.leafTriangles, (unsigned long long)s.clusters,
        s.leafClusters ? double(s.levelTriangles[0]) / double(s.leafClusters) : 0.0, s.levels,
        (unsigned long long)s.rootClusters, s.rootClusters == 1 ? "" : "s", (unsigned long long)s.relaxedGroups);
    if (s.zeroScaleInstances)
      std::printf("left out %u instance%s of zero scale (they show nothing)\n", s.zeroScaleInstances,
                  s.zeroScaleInstances == 1 ? "" : "s");
    std::printf(
        "time: DAG %.2f s (%.2f M leaf triangles/s on %d threads), total %.2f s; peak memory %.1f MB (%.0f bytes per "
        "leaf triangle)\n",
        s.buildSeconds, double(s.leafTriangles) / 1e6 / std::max(s.buildSeconds, 1e-9), args->threads, total,
        double(rss) / 1e6, double(rss) / double(std::max<uint64_t>(s.leafTriangles, 1)));
    if (s.repair.degenerateFaces || s.repair.duplicateFaces || s.repair.nonManifoldEdges || s.repair.splitVertices ||
        s.repair.flippedFaces || s.repair.dissolvedVertices)
      std::printf(
          "repaired: %zu degenerate and %zu duplicate faces dropped, %zu folding vertices taken out, %zu faces turned "
          "to agree "
          "with their neighbours, %zu non-manifold edges, %zu vertices split\n",
          s.repair.degenerateFaces, s.repair.duplicateFaces, s.repair.dissolvedVertices, s.repair.flippedFaces,
          s.repair.nonManifoldEdges, s.repair.splitVertices);
    for (const UnreducedMesh& u : s.unreduced)
      std::printf("note: %s keeps %llu root clusters for %llu connected component%s (%llu triangles): %s\n",
                  u.mesh.c_str(), (unsigned long long)u.rootClusters, (unsigned long long)u.roots.components,
                  u.roots.components == 1 ? "" : "s", (unsigned long long)u.roots.triangles, u.reason.c_str());
    exitCode = 0;
  });
}

}  // namespace vgeo
