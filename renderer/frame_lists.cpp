// frame_lists.cpp: the frame's growing lists (traversal queue, draw list, triangle list, patch list):
// their buffers, their capacities, and their growth after a frame that overflowed one, bounded by what
// one storage buffer addresses and by the frame memory limit (--max-frame-memory).
#include <algorithm>
#include <cstdio>
#include <string>

#include "gpu_renderer.h"

namespace vgeo {

void GpuRenderer::createQueueAndDrawList() {
  VkDeviceSize range = vk_.properties().limits.maxStorageBufferRange;
  queueCapacity_ = uint32_t(std::min<VkDeviceSize>(queueCapacity_, range / 8));
  // A triangle-list entry holds the draw-list entry in 25 bits.
  drawCapacity_ = uint32_t(std::min<VkDeviceSize>({drawCapacity_, range / 8, VGEO_MAX_DRAW_ENTRIES}));
  triangleCapacity_ = uint32_t(std::min<VkDeviceSize>(triangleCapacity_, range / 4));
  // A visibility-buffer id holds the patch-list slot in 20 bits.
  patchCapacity_ = uint32_t(std::min<VkDeviceSize>({patchCapacity_, range / 8, VGEO_MAX_PATCH_ENTRIES}));
  queue_ = vk_.createBuffer(VkDeviceSize(queueCapacity_) * 8, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  deferredItems_ = vk_.createBuffer(VkDeviceSize(queueCapacity_) * 8, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  drawList_ = vk_.createBuffer(VkDeviceSize(drawCapacity_) * 8, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  triangleList_ = vk_.createBuffer(VkDeviceSize(triangleCapacity_) * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  patchList_ = vk_.createBuffer(VkDeviceSize(patchCapacity_) * 8, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  patchDraws_ = vk_.createBuffer(VkDeviceSize(patchCapacity_) * sizeof(VkDrawIndirectCommand),
                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
  patchEntries_ = vk_.createBuffer(VkDeviceSize(drawCapacity_) * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  // Every queue slot starts unwritten; consumers put them back that way.
  VkCommandBuffer cmd = vk_.beginCommands();
  vkCmdFillBuffer(cmd, queue_.buffer, 0, VK_WHOLE_SIZE, VGEO_INVALID);
  vk_.submitAndWait(cmd);
}

void GpuRenderer::setCapacities(uint32_t queueItems, uint32_t drawEntries, uint32_t triangles, uint32_t patches) {
  vkDeviceWaitIdle(vk_.device());
  queue_.reset();
  deferredItems_.reset();
  drawList_.reset();
  triangleList_.reset();
  patchList_.reset();
  patchDraws_.reset();
  patchEntries_.reset();
  patchCapacity_ = std::max(patches, 1u);
  queueCapacity_ = std::max(queueItems, 1u);
  drawCapacity_ = std::max(drawEntries, 1u);
  triangleCapacity_ = std::max(triangles, 1u);
  createQueueAndDrawList();
  writeDescriptors();
}

// Grow what overflowed, for the next frame: to at least what this frame asked for, within what one
// storage buffer can address and the frame memory limit; a cut that cannot fit stops here.
void GpuRenderer::growOverflowedLists(const shaderio::Counters& c, float tau) {
  if (!(c.queueOverflow || c.drawOverflow || c.triangleOverflow || c.patchOverflow)) return;
  const uint64_t range = vk_.properties().limits.maxStorageBufferRange;
  struct List {
    const char* name;
    bool overflowed;
    uint32_t capacity;
    uint64_t needed, bytesEach, most;
  } lists[4] = {
      {"queue items", c.queueOverflow != 0, queueCapacity_, std::max(c.queueHighWater, c.deferredItems), 8, range / 8},
      {"draw-list entries", c.drawOverflow != 0, drawCapacity_, c.drawCount, 8,
       std::min<uint64_t>(range / 8, VGEO_MAX_DRAW_ENTRIES)},
      {"triangles", c.triangleOverflow != 0, triangleCapacity_, c.trianglesDrawn, 4, range / 4},
      {"patches", c.patchOverflow != 0, patchCapacity_, c.patchesDrawn, 8,
       std::min<uint64_t>(range / 8, VGEO_MAX_PATCH_ENTRIES)}};
  char tauText[32];
  std::snprintf(tauText, sizeof tauText, "%g", double(tau));
  uint64_t neededBytes = 0, wantedBytes = 0, want[4];
  for (int i = 0; i < 4; i++) {
    const List& l = lists[i];
    const uint64_t needed = l.overflowed ? std::max<uint64_t>(l.needed, uint64_t(l.capacity) + 1) : l.capacity;
    if (needed > l.most)
      throw FrameMemoryError(std::string("the cut at tau ") + tauText + " needs " + std::to_string(needed) + " " +
                             l.name + ", more than one buffer of " + std::to_string(range >> 20) +
                             " MiB (maxStorageBufferRange) holds on this device: raise --tau or render a smaller view");
    want[i] =
        std::min<uint64_t>(l.overflowed ? std::max<uint64_t>(uint64_t(l.capacity) * 2, needed * 5 / 4) : l.capacity,
                           std::min<uint64_t>(l.most, UINT32_MAX / 2));
    neededBytes += needed * l.bytesEach;
    wantedBytes += want[i] * l.bytesEach;
  }
  if (neededBytes > frameMemoryLimit_)
    throw FrameMemoryError(std::string("the cut at tau ") + tauText + " needs " + std::to_string(neededBytes >> 20) +
                           " MiB of frame lists (" + std::to_string(c.drawCount) + " clusters, " +
                           std::to_string(c.trianglesDrawn) + " triangles), past the limit of " +
                           std::to_string(frameMemoryLimit_ >> 20) +
                           " MiB (--max-frame-memory): raise --tau or the limit");
  if (wantedBytes > frameMemoryLimit_)  // room to grow is a nicety: just what was asked for then
    for (int i = 0; i < 4; i++)
      want[i] = lists[i].overflowed ? std::max<uint64_t>(lists[i].needed, uint64_t(lists[i].capacity) + 1)
                                    : lists[i].capacity;
  setCapacities(uint32_t(want[0]), uint32_t(want[1]), uint32_t(want[2]), uint32_t(want[3]));
}

}  // namespace vgeo
