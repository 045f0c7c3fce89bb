// build_scene.h: the whole builder, from a mesh file to the .vgeo arrays (build_scene.cpp).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "../common/section_sink.h"
#include "builder.h"

namespace vgeo {

struct SceneBuildOptions {
  int subdivisionLevels = 0;
  int threads = 1;
  // Inputs without normals (OBJ, OFF, PLY): faces meeting at more than this many degrees get a hard
  // edge; 180 smooths everything. Subdivided cages always get the limit surface's normals.
  float creaseAngleDegrees = 180.0f;
  uint32_t groupSize = 16;  // clusters a group aims at (BuildOptions::groupSize)
  std::function<void(double fraction, const char* stage)> progress;
};

// A mesh whose DAG ended with more root clusters than its root level has connected components, and why.
struct UnreducedMesh {
  std::string mesh;  // the file, or the glTF mesh's name
  uint64_t rootClusters = 0;
  SurfaceTopology roots;  // of the root level
  std::string reason;
};

struct SceneBuildStats {
  uint64_t inputTriangles = 0;  // of the input file's faces, fanned
  uint64_t leafTriangles = 0;   // after subdivision: the finest level
  uint64_t clusters = 0;
  uint64_t leafClusters = 0;
  uint64_t clusterTriangles = 0;  // over all levels
  uint32_t levels = 0;
  std::vector<uint64_t> levelClusters;  // summed over geometries
  std::vector<uint64_t> levelTriangles;
  uint64_t rootClusters = 0;
  uint64_t relaxedGroups = 0;
  uint64_t stuckGroups = 0;
  uint32_t geometries = 0;
  uint32_t instances = 0;
  uint32_t zeroScaleInstances = 0;  // left out: they show nothing
  RepairReport repair;              // summed over meshes
  std::vector<UnreducedMesh> unreduced;
  double loadSeconds = 0.0, subdivideSeconds = 0.0, buildSeconds = 0.0;
  StageTimes stages;  // every step's seconds, the DAG's own steps among them
};

// Loads, repairs, subdivides and builds every mesh of `path` into the sections of `out` (nothing is at
// a VgeoFileSink's path before its commit); throws InputError for bad input. Before the last mesh's
// layout every section's total is expected (SectionSink::expectTotal), so that a file is written in
// place from there on.
void buildScene(const std::string& path, const SceneBuildOptions& options, SceneBuildStats& stats, SectionSink& out);
// The same, into memory.
VgeoData buildScene(const std::string& path, const SceneBuildOptions& options, SceneBuildStats& stats);

}  // namespace vgeo
