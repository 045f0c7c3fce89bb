// scene.h: what the renderer draws: every geometry and instance of one or more .vgeo files, merged into
// one set of arrays (scene.cpp).
#pragma once

#include <string>
#include <vector>

#include "../common/vgeo_file.h"
#include "camera.h"

namespace vgeo {

struct RenderScene {
  VgeoData data;                   // merged arrays, as uploaded to the GPU
  std::vector<uint32_t> bvhDepth;  // per geometry: levels of BVH nodes from the root to the groups
  uint32_t maxBvhDepth = 0;
  uint32_t maxClusters = 0;                    // largest cluster count of a geometry
  uint32_t maxLevels = 0;                      // most DAG levels of a geometry (the lod view's scale)
  glm::vec4 bounds{0.0f};                      // world-space sphere around every instance
  glm::vec3 boxMin{0.0f}, boxMax{0.0f};        // world-space box around every instance's sphere
  glm::vec3 objectMin{0.0f}, objectMax{0.0f};  // world-space box around every instance's vertices (framing)
  uint64_t virtualTriangles = 0;               // leaf triangles summed over instances
  // Per BVH node: for a simplification level's subtree root (a child of a geometry's root), the run of
  // clusters below it as (first cluster, count), what a sweep tests instead of walking the subtree;
  // (0, 0) for other nodes and for a subtree whose clusters are not one run.
  std::vector<glm::uvec2> levelClusterRuns;
  std::vector<glm::uvec2> instanceRoots;  // shaderio_frame.h, SceneArrays
};

// The most instances a scene may hold: sweep runs carry the instance index in VGEO_RUN_INSTANCE_BITS
// bits (shaderio_frame.h). Scenes are counted against it before their instances are made.
constexpr uint64_t kMaxSceneInstances = (uint64_t(1) << VGEO_RUN_INSTANCE_BITS) - 1;

// Loads a .vgeo, or a scene file (JSON, see README: geometries by path, instances with transforms),
// then repeats the instances on an N x N grid when grid > 1. Throws InputError for bad files.
RenderScene loadRenderScene(const std::string& path, uint32_t grid = 1);
// The camera `vgeo render` and `vgeo view` start from: an object (or a few) framed by its own vertices
// from the front (framePoints), a flat scene from low over its near corner (defaultCamera).
Camera sceneCamera(const RenderScene& scene, float fovYDegrees, float aspect);
// Appends `src` to `dst`, shifting every index; returns the index of src's first geometry in dst.
uint32_t appendVgeo(VgeoData& dst, const VgeoData& src);
// Recomputes the derived fields (depths, bounds, counts) after instances changed.
void finishScene(RenderScene& scene);
// Benchmark layouts: a square grid, a random scatter over the same area (random yaw and uniform scale
// 0.7..1.3), or a forest: the grid's rows packed at one bounding diameter, each instance jittered, turned
// and scaled 0.85..1.15, so that from the ground most of it hides behind its first rows.
enum class BenchLayout { Grid, Scatter, Forest };
BenchLayout benchLayoutNamed(const std::string& name);  // "grid", "scatter", "forest"; else throws
// `count` instances of the first geometry of `base` on the x-z plane (benchmarks), seeded.
RenderScene makeBenchScene(const RenderScene& base, uint32_t count, BenchLayout layout, uint64_t seed);

}  // namespace vgeo
