// cut.h: the CPU reference LOD cut and the invariant checker of docs/design.md (cut.cpp, check.cpp),
// apart from the renderer: they read only the .vgeo.
// The renderer's GPU draw list is tested against selectCut; `vgeo check` runs checkVgeo.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "../common/vgeo_file.h"

namespace vgeo {

// What the LOD test needs from a camera, in the geometry's object space.
struct LodView {
  glm::vec3 eye{0.0f};
  float projScale = 1.0f;  // viewport height / (2 tan(fovY / 2))
  float znear = 0.01f;
  float tau = 1.0f;  // allowed projected error, pixels
};

// The cut of one geometry for one view: every cluster with project(self) <= tau < project(parent)
// (invariant 4), in cluster order. No frustum culling.
std::vector<uint32_t> selectCut(const VgeoData& data, uint32_t geometry, const LodView& view);

struct CheckOptions {
  uint32_t cuts = 32;  // random (camera, tau) pairs per geometry
  uint64_t seed = 1;
};
struct CheckResult {
  bool ok = true;
  std::string firstViolation;  // empty when ok
  std::string summary;
  uint64_t cutClusters = 0;  // summed over the checked cuts
  uint64_t cutTriangles = 0;
  uint32_t rootClusters = 0;
  uint64_t checkedPatches = 0;  // patches (regular and ring) checked to pass through their leaf vertices
};
// Checks invariants 1-5 of docs/design.md on every geometry: cluster sizes; shared self per producing group
// and shared parent per group; monotonic errors and enclosing spheres (self spheres also enclose their
// cluster's vertices); the BVH encloses and bounds its groups and reaches each once; every B-spline patch
// passes through its face's leaf vertices (leaves on the limit surface); and for `cuts`
// random views that the cut is watertight (closed geometries: every edge, matched by position, has
// exactly two triangles of opposite orientation; open ones: no edge, matched by vertex id, is covered
// twice the same way) and
// covers every leaf triangle's area exactly once. Stops at the first violation.
CheckResult checkVgeo(const VgeoData& data, const CheckOptions& options);

}  // namespace vgeo
