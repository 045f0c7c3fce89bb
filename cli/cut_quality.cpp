// cut_quality.cpp: what a DAG's cuts cost and how close their pictures come to the leaves', as numbers
// (`bench build` and `bench cut` report them). From fixed views of one geometry at tau 1: the triangles
// the cut lists and the triangles it sends to the rasterizers per covered pixel (what the frame pays),
// and the image error achieved: the share of pixels whose coverage or normal (by more than
// kNormalDegrees) differs from a picture of the leaves (tau 0.01). Leaves are drawn as triangles in
// both (no patches), so the reference is the finest level of the DAG itself.
#include <cmath>

#include "../renderer/gpu_renderer.h"
#include "../renderer/image.h"
#include "bench.h"

namespace vgeo {
namespace {

constexpr float kNormalDegrees = 10.0f;
constexpr float kReferenceTau = 0.01f;

glm::vec3 decodedNormal(const uint8_t* p) { return glm::vec3(p[0], p[1], p[2]) / 127.5f - 1.0f; }

}  // namespace

std::vector<std::pair<std::string, Camera>> qualityViews(const RenderScene& scene, uint32_t width, uint32_t height) {
  const float fov = 60.0f;
  const Camera front = defaultCamera(scene.bounds, scene.boxMin, scene.boxMax, fov, float(width) / float(height));
  const glm::vec3 c(scene.bounds);
  std::vector<std::pair<std::string, Camera>> views;
  // The framing camera turned about the vertical through the centre: front, right, back, left.
  const char* names[4] = {"front", "right", "back", "left"};
  for (int i = 0; i < 4; i++) {
    const float a = float(i) * 1.5707964f;
    const glm::vec3 d = front.eye - c;
    Camera v = front;
    v.eye = c + glm::vec3(std::cos(a) * d.x + std::sin(a) * d.z, d.y, -std::sin(a) * d.x + std::cos(a) * d.z);
    views.push_back({names[i], v});
  }
  // Far: four times the distance, where coarse levels are drawn.
  Camera far = front;
  far.eye = c + (front.eye - c) * 4.0f;
  views.push_back({"far", far});
  return views;
}

nlohmann::ordered_json measureCutQuality(VulkanContext& vk, const RenderScene& scene, uint32_t width, uint32_t height,
                                         float tau) {
  GpuRenderer renderer(vk, scene, width, height);
  auto frame = [&](const Camera& camera, float t) {
    FrameSettings s;
    s.drawView = s.cullView = makeView(camera, width, height, scene.bounds);
    s.tau = t;
    s.mode = VGEO_MODE_NORMAL;
    s.patches = false;
    s.occlusion = Occlusion::Off;
    FrameResult f = renderer.renderFrame(s);
    for (int i = 0; i < 8 && !f.complete; i++) f = renderer.renderFrame(s);
    if (!f.complete) throw std::runtime_error("cut quality: a frame did not complete");
    return f;
  };
  const float cosLimit = std::cos(glm::radians(kNormalDegrees));
  uint64_t covered = 0, listed = 0, drawn = 0, either = 0, coverageDiffers = 0, normalDiffers = 0;
  nlohmann::ordered_json views = nlohmann::json::array();
  for (const auto& [name, camera] : qualityViews(scene, width, height)) {
    const FrameResult cut = frame(camera, tau), leaves = frame(camera, kReferenceTau);
    uint64_t c = 0, e = 0, cd = 0, nd = 0;
    for (size_t i = 0; i + 3 < cut.rgba.size(); i += 4) {
      const bool a = isCovered(&cut.rgba[i]), b = isCovered(&leaves.rgba[i]);
      c += a;
      e += a || b;
      if (a != b)
        cd++;
      else if (a && glm::dot(glm::normalize(decodedNormal(&cut.rgba[i])),
                             glm::normalize(decodedNormal(&leaves.rgba[i]))) < cosLimit)
        nd++;
    }
    nlohmann::ordered_json v;
    v["view"] = name;
    v["covered_pixels"] = c;
    v["clusters"] = cut.counters.drawCount;
    v["triangles_listed"] = cut.counters.triangles;
    v["triangles_drawn"] = cut.trianglesDrawn;
    v["pixel_error"] = e ? double(cd + nd) / double(e) : 0.0;
    views.push_back(v);
    covered += c;
    listed += cut.counters.triangles;
    drawn += cut.trianglesDrawn;
    either += e;
    coverageDiffers += cd;
    normalDiffers += nd;
  }
  nlohmann::ordered_json q;
  q["width"] = width;
  q["height"] = height;
  q["tau"] = tau;
  q["reference_tau"] = kReferenceTau;
  q["normal_degrees"] = kNormalDegrees;
  // Over all views: per covered pixel of the cut's pictures, and the share of pixels covered in either
  // picture that differ (coverage, or normal by more than normal_degrees).
  q["triangles_listed_per_pixel"] = covered ? double(listed) / double(covered) : 0.0;
  q["triangles_drawn_per_pixel"] = covered ? double(drawn) / double(covered) : 0.0;
  q["pixel_error"] = either ? double(coverageDiffers + normalDiffers) / double(either) : 0.0;
  q["coverage_error"] = either ? double(coverageDiffers) / double(either) : 0.0;
  q["views"] = views;
  return q;
}

}  // namespace vgeo
