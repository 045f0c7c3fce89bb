// render_util.h: what the GPU renderer tests share (test_render*.cpp): one device a suite, cameras
// orbiting a scene and coverage masks of frames.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "../renderer/gpu_renderer.h"
#include "../renderer/image.h"
#include "../renderer/reference_cut.h"

namespace vgeo::test {

// A suite of GPU tests: one Vulkan device with the validation layer (synchronization validation on) for
// the whole suite, a scratch folder for the files it writes, and no validation message after any test.
// A suite calls openSuite in its SetUpTestSuite and closeSuite in its TearDownTestSuite.
class GpuSuite : public ::testing::Test {
 protected:
  static void openSuite(const std::string& folder) {
    vk = new VulkanContext({"", true});
    dir = new std::string(std::filesystem::temp_directory_path() / folder);
    std::filesystem::create_directories(*dir);
  }
  static void closeSuite() {
    delete vk;
    delete dir;
    vk = nullptr;
    dir = nullptr;
  }
  void TearDown() override { EXPECT_EQ(vk->validationMessages(), 0u) << "validation messages (see stderr)"; }

  static inline VulkanContext* vk = nullptr;
  static inline std::string* dir = nullptr;
};

// A camera at `distanceInRadii` bounding radii from the scene's centre, looking at it.
inline Camera orbit(const RenderScene& scene, float azimuth, float elevation, float distanceInRadii) {
  Camera c;
  c.target = glm::vec3(scene.bounds);
  c.eye = c.target + scene.bounds.w * distanceInRadii *
                         glm::vec3(std::cos(elevation) * std::cos(azimuth), std::sin(elevation),
                                   std::cos(elevation) * std::sin(azimuth));
  return c;
}

// A frame of `scene` from `camera` at `width` x `height` (culling from the same view), tau `tau`, with its
// draw list read back; without occlusion culling, so that the list is the whole cut (the occlusion tests
// turn it on).
inline FrameSettings frameSettings(const RenderScene& scene, const Camera& camera, float tau, uint32_t width,
                                   uint32_t height) {
  FrameSettings s;
  s.drawView = s.cullView = makeView(camera, width, height, scene.bounds);
  s.tau = tau;
  s.readDrawList = true;
  s.occlusion = Occlusion::Off;
  return s;
}

// Renders `s` until a frame is complete (a few frames at most: an overflow or workers that ran out grow
// the buffers or the workers for the next) and expects its draw list to equal `reference`.
inline FrameResult renderEqualToCut(GpuRenderer& renderer, const FrameSettings& s, const SceneCut& reference) {
  FrameResult result = renderer.renderFrame(s);
  for (int i = 0; i < 8 && !result.complete; i++) result = renderer.renderFrame(s);
  EXPECT_TRUE(result.complete);
  std::string difference;
  EXPECT_TRUE(compareCuts(reference, result.drawList, difference)) << difference;
  return result;
}

// 1 where a frame's pixel is not the clear colour.
inline std::vector<uint8_t> coverage(const FrameResult& r) {
  std::vector<uint8_t> mask(r.rgba.size() / 4);
  for (size_t i = 0; i < mask.size(); i++) mask[i] = isCovered(&r.rgba[4 * i]);
  return mask;
}

// Cracks: pixels of `lod` left uncovered although `full` covers them and every pixel within `radius`
// (Chebyshev distance), so that an allowed shrink of the silhouette by up to radius - 1 pixels is not
// counted. Both masks are width x height.
inline int leaks(const std::vector<uint8_t>& full, const std::vector<uint8_t>& lod, int width, int height, int radius) {
  int count = 0;
  for (int y = radius; y < height - radius; y++)
    for (int x = radius; x < width - radius; x++) {
      bool deep = true;
      for (int dy = -radius; dy <= radius && deep; dy++)
        for (int dx = -radius; dx <= radius && deep; dx++) deep = full[size_t((y + dy) * width + x + dx)];
      if (deep && !lod[size_t(y * width + x)]) count++;
    }
  return count;
}

}  // namespace vgeo::test
