// frame_readback.cpp: what a frame copies back to the host (counters, image, draw list, the pixels'
// clusters, the worker profile) and how the host reads it into the frame's result.
#include <algorithm>
#include <cstring>

#include "gpu_renderer.h"

namespace vgeo {

// Host-visible buffers the frame writes back: the worker profile when profiled, the draw-list copy.
void GpuRenderer::prepareReadbacks(const FrameSettings& settings, bool profile) {
  if (profile) {
    const VkDeviceSize bytes = VkDeviceSize(persistentWorkgroups_) * VGEO_PROFILE_WORKER_WORDS * 4;
    if (workerProfile_.size < bytes) {
      vkDeviceWaitIdle(vk_.device());
      workerProfile_.reset();
      workerProfile_ = vk_.createBuffer(bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
      writeDescriptors();
    }
    std::memset(workerProfile_.mapped, 0, bytes);
  }
  auto sized = [&](Buffer& readback, const Buffer& source) {
    if (readback.size == source.size) return;
    readback.reset();
    readback = vk_.createBuffer(source.size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
  };
  if (settings.readDrawList || settings.readPixelClusters) sized(drawListReadback_, drawList_);
  if (settings.readPixelClusters) {
    sized(visibilityReadback_, visibility_);
    sized(patchListReadback_, patchList_);
  }
}

// 9. Copies back: counters, image, draw list.
void GpuRenderer::recordReadback(VkCommandBuffer cmd, const FrameSettings& settings) {
  VkBufferCopy all{0, 0, sizeof(shaderio::Counters)};
  vkCmdCopyBuffer(cmd, counters_.buffer, countersReadback_.buffer, 1, &all);
  if (settings.readImage && settings.draw) {
    // The colour from the render pass's GENERAL (and the resolve's writes) to the copy's layout.
    layoutBarrier(cmd, color_, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                  VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                  VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_TRANSFER_READ_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {width_, height_, 1};
    vkCmdCopyImageToBuffer(cmd, color_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, imageReadback_.buffer, 1, &region);
  }
  if (settings.readDrawList || settings.readPixelClusters) {
    VkBufferCopy list{0, 0, drawList_.size};
    vkCmdCopyBuffer(cmd, drawList_.buffer, drawListReadback_.buffer, 1, &list);
  }
  if (settings.readPixelClusters) {  // the visibility buffer (after the resolve) and the patch list it names
    globalBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                  VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    VkBufferCopy pixels{0, 0, visibility_.size}, patchList{0, 0, patchList_.size};
    vkCmdCopyBuffer(cmd, visibility_.buffer, visibilityReadback_.buffer, 1, &pixels);
    vkCmdCopyBuffer(cmd, patchList_.buffer, patchListReadback_.buffer, 1, &patchList);
  }
  globalBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                VK_ACCESS_HOST_READ_BIT);
}

// Copies what the frame left in host-visible memory into the result: counters, tessellator statistics,
// image, draw list, worker profile.
void GpuRenderer::readResults(const FrameSettings& settings, const shaderio::FrameData& frame, bool profile,
                              bool intoVisibility, FrameResult& result) {
  std::memcpy(&result.counters, countersReadback_.mapped, sizeof(result.counters));
  auto& c = result.counters;
  // The frame's totals where the late pass counted its own (begin_late_pass.glsl).
  c.visibleInstances += c.earlyVisibleInstances;
  c.budgetExits += c.earlyBudgetExits;
  const bool patches = frame.drawPatches != 0u, cullTriangles = frame.triangleCull != 0u;
  lastCullItems_ = settings.traversal == Traversal::Persistent ? c.cullItems : 0u;
  result.softwareTriangles =
      std::min(c.softwareTriangles, triangleCapacity_) + std::min(c.earlySoftwareTriangles, triangleCapacity_);
  result.trianglesDrawn = cullTriangles ? c.trianglesDrawn - c.triangleOverflow : c.triangles;
  result.patchesDrawn = std::min(c.patchesDrawn, patchCapacity_);
  result.softwarePatches = std::min(c.softwarePatches, patchCapacity_);
  if (patches && statistics_ && !intoVisibility) {  // the query runs around the tessellated draw, in the depth pass
    uint64_t primitives = 0;
    vkCheck(vkGetQueryPoolResults(vk_.device(), statistics_, 0, 1, sizeof(primitives), &primitives, sizeof(primitives),
                                  VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
            "vkGetQueryPoolResults (statistics)");
    result.patchTriangles = int64_t(primitives) + c.softwarePatchTriangles;
  } else if (!patches || intoVisibility) {
    result.patchTriangles = c.softwarePatchTriangles;
  }
  if (settings.readImage && settings.draw) {
    result.rgba.resize(size_t(width_) * height_ * 4);
    std::memcpy(result.rgba.data(), imageReadback_.mapped, result.rgba.size());
    if (settings.bgraTarget)  // back to R, G, B, A
      for (size_t i = 0; i < result.rgba.size(); i += 4) std::swap(result.rgba[i], result.rgba[i + 2]);
  }
  if (settings.readDrawList) {
    uint32_t n = std::min(c.drawCount, drawCapacity_);
    const uint32_t* p = static_cast<const uint32_t*>(drawListReadback_.mapped);
    result.drawList.resize(n);
    for (uint32_t i = 0; i < n; i++) result.drawList[i] = {p[2 * i], p[2 * i + 1] & ~VGEO_DRAW_PATCHES_BIT};
  }
  if (settings.readPixelClusters && intoVisibility) {
    // Each pixel's id (shaderio_frame.h, the visibility buffer): a triangle-list word, or a patch-list slot
    // whose entry's first word names the draw-list entry the same way.
    const uint64_t* pixels = static_cast<const uint64_t*>(visibilityReadback_.mapped);
    const uint32_t* draws = static_cast<const uint32_t*>(drawListReadback_.mapped);
    const uint32_t* patchList = static_cast<const uint32_t*>(patchListReadback_.mapped);
    std::vector<uint64_t> keys;
    for (size_t i = 0; i < size_t(width_) * height_; i++) {
      if (pixels[i] == 0) continue;
      const uint64_t id = pixels[i] & ((uint64_t(1) << VGEO_VISIBILITY_ID_BITS) - 1);
      const uint32_t word = (id & VGEO_VISIBILITY_PATCH_BIT)
                                ? patchList[2 * ((id & ~VGEO_VISIBILITY_PATCH_BIT) >> VGEO_PATCH_TRIANGLE_BITS)]
                                : uint32_t(id);
      const uint32_t entry = word >> VGEO_TRIANGLE_BITS;
      keys.push_back(uint64_t(draws[2 * entry]) << 32 | (draws[2 * entry + 1] & ~VGEO_DRAW_PATCHES_BIT));
    }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    for (uint64_t k : keys) result.pixelClusters.push_back({uint32_t(k >> 32), uint32_t(k)});
  }
  if (profile) {
    const uint32_t* p = static_cast<const uint32_t*>(workerProfile_.mapped);
    result.workerProfile.assign(p, p + size_t(persistentWorkgroups_) * VGEO_PROFILE_WORKER_WORDS);
  }
}

}  // namespace vgeo
