// reference_cut.cpp: the CPU reference of what the GPU traversals must list for a whole scene: for every
// instance whose bounds meet the frustum, every cluster whose self sphere meets it and that passes the
// cut rule. Same formulas as common.glsl (shaderio.h's projectedError), in float. Clusters whose frustum
// or LOD test value lies within a small relative epsilon of its decision boundary are reported apart:
// rounding may decide them either way on a GPU; every other cluster must match exactly.
#include <cmath>

#include "reference_cut.h"

namespace vgeo {
namespace {

// Smallest signed distance of the sphere's far side to a frustum plane: < 0 means outside.
float frustumMargin(const View& view, glm::vec4 s) {
  float margin = INFINITY;
  for (const auto& p : view.planes) margin = std::min(margin, glm::dot(glm::vec3(p), glm::vec3(s)) + p.w + s.w);
  return margin;
}

}  // namespace

SceneCut selectSceneCut(const RenderScene& scene, const View& cull, float tau, float epsilon) {
  SceneCut cut;
  const VgeoData& d = scene.data;
  for (uint32_t i = 0; i < d.instances.size(); i++) {
    const auto& inst = d.instances[i];
    const auto& g = d.geometries[inst.geometry];
    glm::vec4 bounds = shaderio::worldSphere(inst, g.boundsSphere);
    float boundsMargin = frustumMargin(cull, bounds);
    if (boundsMargin < -epsilon * bounds.w) continue;  // clearly outside: the GPU culls it too
    for (uint32_t c = g.clusterOffset; c < g.clusterOffset + g.clusterCount; c++) {
      const auto& cl = d.clusters[c];
      glm::vec4 self = shaderio::worldSphere(inst, cl.selfSphere);
      float margin = frustumMargin(cull, self);
      float selfError =
          shaderio::projectedError(self, cl.selfError * inst.maxScale, cull.eye, cull.projScale, cull.znear);
      float parentError =
          shaderio::projectedError(shaderio::worldSphere(inst, cl.parentSphere), cl.parentError * inst.maxScale,
                                   cull.eye, cull.projScale, cull.znear);
      const bool leaf = cl.producer == VGEO_NO_GROUP;
      bool drawn = margin >= 0.0f && shaderio::inCut(selfError, parentError, tau, leaf);
      bool borderline =
          std::abs(margin) <= epsilon * std::max(self.w, 1e-30f) || std::abs(boundsMargin) <= epsilon * bounds.w ||
          (!leaf && std::abs(selfError - tau) <= epsilon * tau) || std::abs(parentError - tau) <= epsilon * tau;
      if ((inst.flags & VGEO_INSTANCE_CONE_CULL) && drawn) {
        const shaderio::ClusterCone& cc = d.clusterCones[c];
        glm::vec3 axis = glm::normalize(glm::vec3(glm::dot(glm::vec3(inst.row0), glm::vec3(cc.cone)),
                                                  glm::dot(glm::vec3(inst.row1), glm::vec3(cc.cone)),
                                                  glm::dot(glm::vec3(inst.row2), glm::vec3(cc.cone))));
        glm::vec4 tight = shaderio::worldSphere(inst, cc.sphere);
        drawn = !shaderio::clusterFacesAway(glm::vec4(axis, cc.cone.w), tight, cull.eye);
        if (cc.cone.w >= 0.0f) {
          glm::vec3 v = glm::vec3(tight) - cull.eye;
          float coneMargin = glm::dot(v, axis) - (cc.cone.w * glm::length(v) + tight.w * (1.0f + cc.cone.w));
          borderline = borderline || std::abs(coneMargin) <= epsilon * (glm::length(v) + tight.w);
        }
      }
      if (borderline)
        cut.borderline.push_back({i, c});
      else if (drawn)
        cut.entries.push_back({i, c});
    }
  }
  return cut;
}

bool compareCuts(const SceneCut& reference, std::vector<CutEntry> gpu, std::string& firstDifference, bool subset) {
  auto key = [](const CutEntry& e) { return uint64_t(e.instance) << 32 | e.cluster; };
  std::vector<uint64_t> want, got, border;
  for (const auto& e : reference.entries) want.push_back(key(e));
  for (const auto& e : reference.borderline) border.push_back(key(e));
  for (const auto& e : gpu) got.push_back(key(e));
  std::sort(want.begin(), want.end());
  std::sort(border.begin(), border.end());
  std::sort(got.begin(), got.end());
  if (std::adjacent_find(got.begin(), got.end()) != got.end()) {
    uint64_t k = *std::adjacent_find(got.begin(), got.end());
    firstDifference =
        "GPU lists (instance " + std::to_string(k >> 32) + ", cluster " + std::to_string(uint32_t(k)) + ") twice";
    return false;
  }
  // Every reference entry must be listed (unless a subset is enough); every listed entry must be in the
  // reference or borderline.
  for (uint64_t k : subset ? std::vector<uint64_t>() : want)
    if (!std::binary_search(got.begin(), got.end(), k)) {
      firstDifference =
          "GPU misses (instance " + std::to_string(k >> 32) + ", cluster " + std::to_string(uint32_t(k)) + ")";
      return false;
    }
  for (uint64_t k : got)
    if (!std::binary_search(want.begin(), want.end(), k) && !std::binary_search(border.begin(), border.end(), k)) {
      firstDifference = "GPU lists (instance " + std::to_string(k >> 32) + ", cluster " + std::to_string(uint32_t(k)) +
                        ") which the CPU does not";
      return false;
    }
  return true;
}

}  // namespace vgeo
