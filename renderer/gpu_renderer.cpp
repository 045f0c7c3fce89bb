// gpu_renderer.cpp: the frame. renderFrame() is its steps; runPasses() records the passes, in this order:
//   1. reset counters            (transfer)
//   2. cull_instances.comp       1 or 64 lanes an instance (64 on GPUs up to 4,096 instances) -> queue of
//                                (instance, level subtree root), or of (instance, BVH root) for flat; in
//                                scenes of up to 3 instances a persistent worker on GPUs, the workers cull
//                                them first themselves (cull_instances.glsl), in the traversal's dispatch
//   3. traversal                 persistent: one dispatch of resident workgroups draining the queue
//                                levels: per depth, prepare_level.comp then traverse_level.comp (indirect)
//                                flat: prepare_flat.comp then traverse_flat.comp (one thread a cluster)
//   4. draw_arguments.glsl       triangle-culling dispatch (or draw) arguments from the draw-list count:
//                                the persistent traversal's last worker, reset_flat.comp, finalize.comp
//   5. cull_triangles.comp       one workgroup a listed cluster -> triangle list of what can make fragments
//      finalize_triangles.comp   indirect draw arguments from the triangle count
//   6. render pass: one vkCmdDrawIndirect of the listed triangles (draw.vert, draw.frag); without
//      triangle culling, of 384 vertices x listed clusters; then one of the listed patches, one vertex
//      a patch (patch.vert, patch.tesc, patch.tese)
//   7. copies back: counters (and the image / draw list when asked), read once the frame is done
// No host read-back happens inside the frame; the host reads the counters after it, and a frame that
// overflowed grows the buffers for the next one.
#include "gpu_renderer.h"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <functional>
#include <iterator>
#include <stdexcept>

namespace vgeo {
namespace {

// lavapipe ends every loop after 65,535 iterations per invocation (docs/gpu-notes.md, 1): persistent workers
// leave on their own well before, holding nothing, and enough of them are dispatched to carry on.
constexpr uint32_t kLavapipeIterationBudget = 50000;
// lavapipe starts the workgroups one after another, each for some microseconds even when the queue is
// already empty, so late workers are pure cost: few of them (bench/README.md, cut selection). A frame
// whose workers all run out of budget is reported incomplete and the next one runs twice as many
// (renderFrame).
constexpr uint32_t kLavapipeWorkgroups = 4;
constexpr uint32_t kMaxPersistentWorkgroups = 4096;
// Up to this many instances the persistent traversal runs two workgroups an SM (three up to
// VGEO_CULL_SPREAD_INSTANCES), four above: larger scenes keep more workers busy, smaller ones only poll
// more empty slots (bench/README.md, cut selection).
constexpr size_t kFewWorkgroupsInstances = 32768;
// The patch draw as instances of this many patches. lavapipe tessellates each instance in one run whose
// output is indexed with 16 bits: 15 patches at factor 64 (4,225 vertices each) stay under 65,536,
// where one instance of all patches joined unrelated vertices in close-ups. GPUs: one instance holds
// many (the count has no effect on the picture).
constexpr uint32_t kLavapipePatchesPerInstance = 15, kPatchesPerInstance = 4096;
// Frame start, then the end of instance culling, traversal, triangle culling and the draw.
constexpr uint32_t kTimestamps = 8;

void globalBarrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkAccessFlags srcAccess, VkPipelineStageFlags dst,
                   VkAccessFlags dstAccess) {
  VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  b.srcAccessMask = srcAccess;
  b.dstAccessMask = dstAccess;
  vkCmdPipelineBarrier(cmd, src, dst, 0, 1, &b, 0, nullptr, 0, nullptr);
}
void computeToCompute(VkCommandBuffer cmd) {
  globalBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT,
                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
}

double msSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

// The draws' geometry stages that read what the compute passes wrote (lists, counters).
VkPipelineStageFlags GpuRenderer::drawShaderStages() const {
  return VK_PIPELINE_STAGE_VERTEX_SHADER_BIT |
         (vk_.tessellation()
              ? VK_PIPELINE_STAGE_TESSELLATION_CONTROL_SHADER_BIT | VK_PIPELINE_STAGE_TESSELLATION_EVALUATION_SHADER_BIT
              : 0u);
}

const char* traversalName(Traversal t) {
  return t == Traversal::Persistent ? "persistent" : t == Traversal::Levels ? "levels" : "flat";
}

GpuRenderer::GpuRenderer(VulkanContext& context, const RenderScene& scene, uint32_t width, uint32_t height)
    : vk_(context), scene_(scene), width_(width), height_(height) {
  const VgeoData& d = scene.data;
  VkDeviceSize range = vk_.properties().limits.maxStorageBufferRange;
  // The scene's arrays, each uploaded once to its binding (shaderio.h, VGEO_BINDING_*).
  auto bytes = [](const auto& v) { return v.size() * sizeof(v[0]); };
  struct SceneArray {
    uint32_t binding;
    const void* data;
    size_t bytes;
  } sections[] = {
      {VGEO_BINDING_GEOMETRIES, d.geometries.data(), bytes(d.geometries)},
      {VGEO_BINDING_INSTANCES, d.instances.data(), bytes(d.instances)},
      {VGEO_BINDING_POSITIONS, d.positions.data(), bytes(d.positions)},
      {VGEO_BINDING_NORMALS, d.normals.data(), bytes(d.normals)},
      {VGEO_BINDING_CLUSTERS, d.clusters.data(), bytes(d.clusters)},
      {VGEO_BINDING_CLUSTER_VERTICES, d.clusterVertices.data(), bytes(d.clusterVertices)},
      {VGEO_BINDING_CLUSTER_TRIANGLES, d.clusterTriangles.data(), bytes(d.clusterTriangles)},
      {VGEO_BINDING_GROUPS, d.groups.data(), bytes(d.groups)},
      {VGEO_BINDING_NODES, d.nodes.data(), bytes(d.nodes)},
      {VGEO_BINDING_CLUSTER_CONES, d.clusterCones.data(), bytes(d.clusterCones)},
      {VGEO_BINDING_CONTROL_POINTS, d.controlPoints.data(), bytes(d.controlPoints)},
      {VGEO_BINDING_CAGE_FACES, d.cageFaces.data(), bytes(d.cageFaces)},
      {VGEO_BINDING_CAGE_FACE_VERTICES, d.cageFaceVertices.data(), bytes(d.cageFaceVertices)},
      {VGEO_BINDING_PATCHES, d.patches.data(), bytes(d.patches)},
      {VGEO_BINDING_PATCH_POINTS, d.patchPoints.data(), bytes(d.patchPoints)},
      {VGEO_BINDING_LEVEL_CLUSTER_RUNS, scene.levelClusterRuns.data(), bytes(scene.levelClusterRuns)},
      {VGEO_BINDING_INSTANCE_ROOTS, scene.instanceRoots.data(), bytes(scene.instanceRoots)},
  };
  // Sweep runs carry their length above the instance index (shaderio.h, VGEO_ITEM_RUN_BIT).
  if (d.instances.size() >= (size_t(1) << VGEO_RUN_INSTANCE_BITS))
    throw std::runtime_error("scene too large: " + std::to_string(d.instances.size()) + " instances (at most " +
                             std::to_string((1u << VGEO_RUN_INSTANCE_BITS) - 1) + ")");
  for (const auto& s : sections) {
    if (s.bytes > range)
      throw std::runtime_error("scene too large for this device: a buffer of " + std::to_string(s.bytes >> 20) +
                               " MiB exceeds maxStorageBufferRange (" + std::to_string(range >> 20) + " MiB)");
    sceneBuffers_.push_back({s.binding, vk_.createBuffer(s.bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT)});
    vk_.upload(sceneBuffers_.back().second, s.data, s.bytes);
  }
  frameData_ = vk_.createBuffer(sizeof(shaderio::FrameData), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
  counters_ = vk_.createBuffer(sizeof(shaderio::Counters),
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
  workerProfile_ = vk_.createBuffer(16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
  countersReadback_ = vk_.createBuffer(sizeof(shaderio::Counters), VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
  imageReadback_ = vk_.createBuffer(VkDeviceSize(width_) * height_ * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
  // The visibility buffer and the overdraw counts, a word or two a pixel (a placeholder where the software
  // rasterizer cannot run: no 64-bit atomics, or a picture past one buffer's range).
  const VkDeviceSize pixels = VkDeviceSize(width_) * height_;
  const bool software = vk_.int64Atomics() && pixels * 8 <= range;
  visibility_ = vk_.createBuffer(software ? pixels * 8 : 16,
                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  overdraw_ = vk_.createBuffer(software ? pixels * 4 : 16,
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);

  if (vk_.isLavapipe()) {
    claimMode_ = 1;
    iterationBudget_ = kLavapipeIterationBudget;
    persistentWorkgroups_ = kLavapipeWorkgroups;
  } else {
    // Four workgroups an SM where NVIDIA tells the SM count, two in scenes of up to
    // kFewWorkgroupsInstances instances, three in those of up to VGEO_CULL_SPREAD_INSTANCES; never all
    // the device holds: claiming past the frontier makes every extra workgroup a poller of empty slots.
    const size_t instances = scene_.data.instances.size();
    const uint32_t perSm = instances <= VGEO_CULL_SPREAD_INSTANCES ? 3u
                           : instances <= kFewWorkgroupsInstances  ? 2u
                                                                   : 4u;
    persistentWorkgroups_ = 128 * perSm;
    if (vk_.hasDeviceExtension(VK_NV_SHADER_SM_BUILTINS_EXTENSION_NAME)) {
      VkPhysicalDeviceShaderSMBuiltinsPropertiesNV sm{
          VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_SM_BUILTINS_PROPERTIES_NV};
      VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
      props.pNext = &sm;
      vkGetPhysicalDeviceProperties2(vk_.physicalDevice(), &props);
      persistentWorkgroups_ = std::max(1u, sm.shaderSMCount * perSm);
    }
  }
  createTargets();
  createQueueAndDrawList();
  createPipelines(software);
  writeDescriptors();
  // Warm-up: one persistent dispatch over an empty queue (all workers leave at once). On lavapipe the
  // first dispatch of a pipeline also compiles it, and in that first run workers were measured to
  // starve and be cut off; later runs were sound.
  {
    shaderio::FrameData frame{};
    frame.claimMode = claimMode_;
    frame.iterationBudget = iterationBudget_;
    frame.queueCapacity = queueCapacity_;
    std::memcpy(frameData_.mapped, &frame, sizeof(frame));
    VkCommandBuffer cmd = vk_.beginCommands();
    recordCounterReset(cmd);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, persistent_);
    vkCmdDispatch(cmd, persistentWorkgroups_, 1, 1);
    vk_.submitAndWait(cmd);
  }
  VkQueryPoolCreateInfo q{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  q.queryType = VK_QUERY_TYPE_TIMESTAMP;
  q.queryCount = kTimestamps;
  vkCheck(vkCreateQueryPool(vk_.device(), &q, nullptr, &queries_), "vkCreateQueryPool");
  if (vk_.pipelineStatistics()) {
    VkQueryPoolCreateInfo stats{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    stats.queryType = VK_QUERY_TYPE_PIPELINE_STATISTICS;
    stats.queryCount = 1;
    stats.pipelineStatistics = VK_QUERY_PIPELINE_STATISTIC_CLIPPING_INVOCATIONS_BIT;
    vkCheck(vkCreateQueryPool(vk_.device(), &stats, nullptr, &statistics_), "vkCreateQueryPool (statistics)");
  }
}

GpuRenderer::~GpuRenderer() {
  VkDevice dev = vk_.device();
  vkDeviceWaitIdle(dev);
  for (VkPipeline p : {cull_, cullSerial_, persistent_, persistentProfile_, level_, prepareLevel_, flat_, prepareFlat_,
                       resetFlat_, finalize_, cullTriangles_, preparePatches_, cullPatches_, finalizeTriangles_, draw_,
                       drawOverdraw_, drawPatches_, drawPatchesOverdraw_, rasterSoftware_})
    vkDestroyPipeline(dev, p, nullptr);
  for (VkPipeline p : resolve_) vkDestroyPipeline(dev, p, nullptr);
  vkDestroyPipelineLayout(dev, layout_, nullptr);
  vkDestroyDescriptorPool(dev, descriptorPool_, nullptr);
  vkDestroyDescriptorSetLayout(dev, setLayout_, nullptr);
  vkDestroyQueryPool(dev, queries_, nullptr);
  if (statistics_) vkDestroyQueryPool(dev, statistics_, nullptr);
  vkDestroySampler(dev, depthSampler_, nullptr);
  vkDestroyFramebuffer(dev, framebuffer_, nullptr);
  vkDestroyRenderPass(dev, renderPass_, nullptr);
  vkDestroyRenderPass(dev, renderPassResolved_, nullptr);
  vkDestroyImageView(dev, colorView_, nullptr);
  vkDestroyImageView(dev, depthView_, nullptr);
  vkDestroyImage(dev, color_, nullptr);
  vkDestroyImage(dev, depth_, nullptr);
  vkFreeMemory(dev, colorMemory_, nullptr);
  vkFreeMemory(dev, depthMemory_, nullptr);
  for (Buffer* b :
       {&frameData_, &counters_, &countersReadback_, &queue_, &drawList_, &drawListReadback_, &imageReadback_,
        &triangleList_, &patchList_, &patchEntries_, &workerProfile_, &visibility_, &overdraw_})
    vk_.destroyBuffer(*b);
  for (auto& [binding, b] : sceneBuffers_) vk_.destroyBuffer(b);
}

void GpuRenderer::writeDescriptors() {
  const Buffer* buffers[kRendererBindings] = {};
  buffers[VGEO_BINDING_FRAME] = &frameData_;
  buffers[VGEO_BINDING_COUNTERS] = &counters_;
  buffers[VGEO_BINDING_QUEUE] = &queue_;
  buffers[VGEO_BINDING_DRAW_LIST] = &drawList_;
  buffers[VGEO_BINDING_TRIANGLE_LIST] = &triangleList_;
  buffers[VGEO_BINDING_PATCH_LIST] = &patchList_;
  buffers[VGEO_BINDING_PATCH_ENTRIES] = &patchEntries_;
  buffers[VGEO_BINDING_WORKER_PROFILE] = &workerProfile_;
  buffers[VGEO_BINDING_VISIBILITY] = &visibility_;
  buffers[VGEO_BINDING_OVERDRAW] = &overdraw_;
  for (const auto& [binding, b] : sceneBuffers_) buffers[binding] = &b;
  const VkDescriptorImageInfo colorImage{VK_NULL_HANDLE, colorView_, VK_IMAGE_LAYOUT_GENERAL},
      depthImage{depthSampler_, depthView_, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL};
  VkDescriptorBufferInfo infos[kRendererBindings];
  VkWriteDescriptorSet writes[kRendererBindings];
  for (uint32_t i = 0; i < kRendererBindings; i++) {
    const VkDescriptorType type = descriptorType(i);
    const bool image = type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE || type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    if (!image && !buffers[i]) throw std::logic_error("binding " + std::to_string(i) + " has no buffer");
    if (!image) infos[i] = {buffers[i]->buffer, 0, VK_WHOLE_SIZE};
    writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                 nullptr,
                 set_,
                 i,
                 0,
                 1,
                 type,
                 i == VGEO_BINDING_COLOR_IMAGE   ? &colorImage
                 : i == VGEO_BINDING_DEPTH_IMAGE ? &depthImage
                                                 : nullptr,
                 image ? nullptr : &infos[i],
                 nullptr};
  }
  vkUpdateDescriptorSets(vk_.device(), kRendererBindings, writes, 0, nullptr);
}

// Resets the counters: all 0 but nodesPending, the instances the persistent workers will cull (earlier
// submissions are ordered before it by the opening barrier); binds the descriptor set for the compute passes.
void GpuRenderer::recordCounterReset(VkCommandBuffer cmd, uint32_t nodesPending) {
  globalBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT,
                VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
  shaderio::Counters zero{};
  zero.nodesPending = nodesPending;
  vkCmdUpdateBuffer(cmd, counters_.buffer, 0, sizeof(zero), &zero);
  globalBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
}

void GpuRenderer::recordInstanceCull(VkCommandBuffer cmd, const FrameSettings& settings) {
  // 1. Reset the counters. 2. Instance culling, unless the persistent traversal's workers do it: then each
  // instance counts as pending until its culling has queued its items (traverse_persistent.comp).
  if (cullsInTraversal(settings)) {
    recordCounterReset(cmd, uint32_t(scene_.data.instances.size()));
    return;
  }
  recordCounterReset(cmd);
  const uint32_t lanes = cullInstanceLanes(settings),
                 instancesPerWorkgroup = lanes == 1 ? 64 : VGEO_CULL_SPREAD_WORKGROUP / lanes;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, lanes == 1 ? cullSerial_ : cull_);
  vkCmdDispatch(cmd, (uint32_t(scene_.data.instances.size()) + instancesPerWorkgroup - 1) / instancesPerWorkgroup, 1,
                1);
  computeToCompute(cmd);
}

void GpuRenderer::recordTraversal(VkCommandBuffer cmd, const FrameSettings& settings) {
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
  // 3. Traversal. Every pass is followed by a barrier before the next reads what it wrote; the last one
  // writes the draw arguments (4., draw_arguments.glsl: the persistent traversal's last worker, the flat
  // traversal's reset pass, finalize.comp after the levels) and is followed by the barrier below.
  auto lastPass = [&](VkPipeline pipeline, uint32_t workgroups) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdDispatch(cmd, workgroups, 1, 1);
  };
  auto dispatch = [&](VkPipeline pipeline, uint32_t workgroups) {
    lastPass(pipeline, workgroups);
    computeToCompute(cmd);
  };
  auto dispatchIndirect = [&](VkPipeline pipeline) {  // sized by the preceding prepare pass
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdDispatchIndirect(cmd, counters_.buffer, offsetof(shaderio::Counters, dispatch));
    computeToCompute(cmd);
  };
  if (settings.traversal == Traversal::Persistent) {
    lastPass(settings.profileWorkers && persistentProfile_ ? persistentProfile_ : persistent_, persistentWorkgroups_);
  } else if (settings.traversal == Traversal::Levels) {
    // The roots' children (queued by instance culling), one level of nodes per dispatch, then the groups:
    // depth windows.
    for (uint32_t level = 0; level < scene_.maxBvhDepth; level++) {
      dispatch(prepareLevel_, 1);
      dispatchIndirect(level_);
    }
    lastPass(finalize_, 1);
  } else {
    dispatch(prepareFlat_, 1);
    dispatchIndirect(flat_);
    lastPass(resetFlat_, (uint32_t(scene_.data.instances.size()) + 63) / 64);
  }
  // Read by triangle culling (indirect dispatch and counters), or else by the draw and the copies.
  globalBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | drawShaderStages() |
                    VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                    VK_ACCESS_TRANSFER_READ_BIT);
}

// 5. Triangle culling: the triangles of the listed clusters that can make a fragment, then the draw's arguments.
void GpuRenderer::recordTriangleCull(VkCommandBuffer cmd, bool patches) {
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, cullTriangles_);
  vkCmdDispatchIndirect(cmd, counters_.buffer, offsetof(shaderio::Counters, dispatch));
  computeToCompute(cmd);
  if (patches) {  // the patch-drawn clusters that triangle culling listed, a workgroup each
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, preparePatches_);
    vkCmdDispatch(cmd, 1, 1, 1);
    computeToCompute(cmd);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, cullPatches_);
    vkCmdDispatchIndirect(cmd, counters_.buffer, offsetof(shaderio::Counters, patchCullDispatch));
    computeToCompute(cmd);
  }
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, finalizeTriangles_);
  vkCmdDispatch(cmd, 1, 1, 1);
  globalBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | drawShaderStages() |
                    VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT);
}

// 6. The software rasterizer: the visibility buffer (or the overdraw counts) cleared, then the triangles
// binned to it drawn into it; read by the resolve after the render pass.
void GpuRenderer::recordSoftwareRaster(VkCommandBuffer cmd) {
  vkCmdFillBuffer(cmd, visibility_.buffer, 0, VK_WHOLE_SIZE, 0);
  vkCmdFillBuffer(cmd, overdraw_.buffer, 0, VK_WHOLE_SIZE, 0);
  globalBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, rasterSoftware_);
  vkCmdDispatchIndirect(cmd, counters_.buffer, offsetof(shaderio::Counters, rasterDispatch));
  globalBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
}

// 8. The resolve of the software rasterizer's pixels where they are nearer than the render pass's
// (resolve.comp), into the colour target.
void GpuRenderer::recordResolve(VkCommandBuffer cmd, uint32_t mode) {
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, resolvePipeline(mode));
  vkCmdDispatch(cmd, (width_ + 7) / 8, (height_ + 7) / 8, 1);
}

// 9. Copies back: counters, image, draw list.
void GpuRenderer::recordReadback(VkCommandBuffer cmd, const FrameSettings& settings) {
  VkBufferCopy all{0, 0, sizeof(shaderio::Counters)};
  vkCmdCopyBuffer(cmd, counters_.buffer, countersReadback_.buffer, 1, &all);
  if (settings.readImage && settings.draw) {
    // The colour from the render pass's GENERAL (and the resolve's writes) to the copy's layout.
    VkImageMemoryBarrier toCopy{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    toCopy.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    toCopy.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    toCopy.oldLayout = VK_IMAGE_LAYOUT_GENERAL;
    toCopy.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    toCopy.srcQueueFamilyIndex = toCopy.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    toCopy.image = color_;
    toCopy.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &toCopy);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {width_, height_, 1};
    vkCmdCopyImageToBuffer(cmd, color_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, imageReadback_.buffer, 1, &region);
  }
  if (settings.readDrawList) {
    VkBufferCopy list{0, 0, drawList_.size};
    vkCmdCopyBuffer(cmd, drawList_.buffer, drawListReadback_.buffer, 1, &list);
  }
  globalBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                VK_ACCESS_HOST_READ_BIT);
}

// 7. The render pass: one indirect draw of the listed hardware triangles, one of the patches.
void GpuRenderer::recordRenderPass(VkCommandBuffer cmd, const FrameSettings& settings) {
  VkClearValue clears[2];
  clears[0].color = {{VGEO_BACKGROUND_R, VGEO_BACKGROUND_G, VGEO_BACKGROUND_B, 1.0f}};
  clears[1].depthStencil = {0.0f, 0};
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  // The resolve writes the background where nothing was drawn, except in the overdraw view (it adds).
  const bool resolved = softwareRaster(settings) != VGEO_RASTER_NONE && settings.mode != VGEO_MODE_OVERDRAW;
  begin.renderPass = resolved ? renderPassResolved_ : renderPass_;
  begin.framebuffer = framebuffer_;
  begin.renderArea = {{0, 0}, {width_, height_}};
  begin.clearValueCount = 2;
  begin.pClearValues = clears;
  const bool patches = drawsPatches(settings);
  if (patches && statistics_) vkCmdResetQueryPool(cmd, statistics_, 0, 1);
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &set_, 0, nullptr);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, settings.mode == VGEO_MODE_OVERDRAW ? drawOverdraw_ : draw_);
  vkCmdDrawIndirect(cmd, counters_.buffer, offsetof(shaderio::Counters, draw), 1, sizeof(VkDrawIndirectCommand));
  // The leaf patches: one more indirect draw, tessellated (patch.tesc, patch.tese).
  if (patches) {
    if (statistics_) vkCmdBeginQuery(cmd, statistics_, 0, 0);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                      settings.mode == VGEO_MODE_OVERDRAW ? drawPatchesOverdraw_ : drawPatches_);
    vkCmdDrawIndirect(cmd, counters_.buffer, offsetof(shaderio::Counters, patchDraw), 1, sizeof(VkDrawIndirectCommand));
    if (statistics_) vkCmdEndQuery(cmd, statistics_, 0);
  }
  vkCmdEndRenderPass(cmd);
}

// The frame's constants (shaderio.h, FrameData) for these settings.
shaderio::FrameData GpuRenderer::frameConstants(const FrameSettings& settings) const {
  shaderio::FrameData frame{};
  frame.viewProjection = settings.drawView.viewProjection;
  for (int i = 0; i < 6; i++) frame.frustum[i] = settings.cullView.planes[i];
  frame.cullEye = glm::vec4(settings.cullView.eye, 1.0f);
  frame.drawEye = glm::vec4(settings.drawView.eye, 1.0f);
  frame.projScale = settings.cullView.projScale;
  frame.tau = settings.tau;
  frame.znear = settings.cullView.znear;
  frame.mode = settings.mode;
  frame.instanceCount = uint32_t(scene_.data.instances.size());
  frame.queueCapacity = queueCapacity_;
  frame.drawCapacity = drawCapacity_;
  frame.iterationBudget = iterationBudget_;
  frame.maxClusters = scene_.maxClusters;
  frame.claimMode = claimMode_;
  frame.queueRoots = settings.traversal == Traversal::Flat ? 1u : 0u;
  frame.sweepBudget = settings.traversal == Traversal::Persistent ? settings.sweepBudget : 0u;
  frame.firstClaimItems = lastCullItems_;
  frame.cullInTraversal = cullsInTraversal(settings) ? 1u : 0u;
  frame.triangleCull = settings.draw && settings.triangleCull ? 1u : 0u;
  frame.triangleCapacity = triangleCapacity_;
  frame.viewportWidth = float(width_);
  frame.viewportHeight = float(height_);
  frame.patches = drawsPatches(settings) ? 1u : 0u;
  frame.patchesPerInstance = vk_.isLavapipe() ? kLavapipePatchesPerInstance : kPatchesPerInstance;
  frame.patchCapacity = patchCapacity_;
  frame.softwareRaster = softwareRaster(settings);
  return frame;
}

// Host-visible buffers the frame writes back: the worker profile when profiled, the draw-list copy.
void GpuRenderer::prepareReadbacks(const FrameSettings& settings, bool profile) {
  if (profile) {
    const VkDeviceSize bytes = VkDeviceSize(persistentWorkgroups_) * VGEO_PROFILE_WORKER_WORDS * 4;
    if (workerProfile_.size < bytes) {
      vkDeviceWaitIdle(vk_.device());
      vk_.destroyBuffer(workerProfile_);
      workerProfile_ = vk_.createBuffer(bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
      writeDescriptors();
    }
    std::memset(workerProfile_.mapped, 0, bytes);
  }
  if (settings.readDrawList && drawListReadback_.size != drawList_.size) {
    vk_.destroyBuffer(drawListReadback_);
    drawListReadback_ = vk_.createBuffer(drawList_.size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
  }
}

// Records and submits the passes in frame order
// and times each: GPU timestamps in one submission, or on lavapipe one submission a pass timed on the
// host.
void GpuRenderer::runPasses(const FrameSettings& settings, const shaderio::FrameData& frame, FrameResult& result) {
  // The frame's passes in order, each with where its time goes (nullptr: the frame's only).
  const bool software = frame.softwareRaster != VGEO_RASTER_NONE;
  struct Pass {
    double* ms;
    bool runs;
    std::function<void(VkCommandBuffer)> record;
  } passes[] = {
      {&result.instanceCullMs, true, [&](VkCommandBuffer cmd) { recordInstanceCull(cmd, settings); }},
      {&result.traversalMs, true, [&](VkCommandBuffer cmd) { recordTraversal(cmd, settings); }},
      {&result.triangleCullMs, frame.triangleCull != 0u,
       [&](VkCommandBuffer cmd) { recordTriangleCull(cmd, frame.patches != 0u); }},
      {&result.rasterMs, software, [&](VkCommandBuffer cmd) { recordSoftwareRaster(cmd); }},
      {&result.drawMs, settings.draw, [&](VkCommandBuffer cmd) { recordRenderPass(cmd, settings); }},
      {&result.resolveMs, settings.draw && software, [&](VkCommandBuffer cmd) { recordResolve(cmd, settings.mode); }},
      {nullptr, true, [&](VkCommandBuffer cmd) { recordReadback(cmd, settings); }},
  };
  static_assert(std::size(passes) + 1 == kTimestamps, "a timestamp before each pass and one after the last");
  const double period = vk_.timestampPeriod();
  const auto start = std::chrono::steady_clock::now();
  if (vk_.isLavapipe() || period == 0.0) {
    // lavapipe's compute timestamps are wrong after the first submission (docs/gpu-notes.md, 3): one submission
    // a pass, timed on the host.
    result.timing = "host-per-submission";
    for (const Pass& pass : passes) {
      if (!pass.runs) continue;
      const auto passStart = std::chrono::steady_clock::now();
      VkCommandBuffer cmd = vk_.beginCommands();
      pass.record(cmd);
      vk_.submitAndWait(cmd);
      if (pass.ms) *pass.ms = msSince(passStart);
    }
    result.frameMs = msSince(start);
  } else {
    result.timing = "gpu-timestamps";
    VkCommandBuffer cmd = vk_.beginCommands();
    vkCmdResetQueryPool(cmd, queries_, 0, kTimestamps);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries_, 0);
    for (uint32_t i = 0; i < std::size(passes); i++) {
      if (passes[i].runs) passes[i].record(cmd);
      vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, i + 1);
    }
    vk_.submitAndWait(cmd);
    uint64_t t[kTimestamps];
    vkCheck(vkGetQueryPoolResults(vk_.device(), queries_, 0, kTimestamps, sizeof(t), t, sizeof(uint64_t),
                                  VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
            "vkGetQueryPoolResults");
    auto ms = [&](uint32_t from, uint32_t to) { return double(t[to] - t[from]) * period * 1e-6; };
    for (uint32_t i = 0; i < std::size(passes); i++)
      if (passes[i].ms) *passes[i].ms = ms(i, i + 1);
    result.frameMs = ms(0, kTimestamps - 1);
  }
}

// Copies what the frame left in host-visible memory into the result: counters, tessellator statistics,
// image, draw list, worker profile.
void GpuRenderer::readResults(const FrameSettings& settings, const shaderio::FrameData& frame, bool profile,
                              FrameResult& result) {
  std::memcpy(&result.counters, countersReadback_.mapped, sizeof(result.counters));
  const auto& c = result.counters;
  const bool patches = frame.patches != 0u, cullTriangles = frame.triangleCull != 0u;
  lastCullItems_ = settings.traversal == Traversal::Persistent ? c.cullItems : 0u;
  result.softwareTriangles = std::min(c.softwareTriangles, triangleCapacity_);
  result.trianglesDrawn = cullTriangles ? std::min(c.trianglesDrawn, triangleCapacity_) : c.triangles;
  result.patchesDrawn = std::min(c.patchesDrawn, patchCapacity_);
  if (patches && statistics_) {
    uint64_t primitives = 0;
    vkCheck(vkGetQueryPoolResults(vk_.device(), statistics_, 0, 1, sizeof(primitives), &primitives, sizeof(primitives),
                                  VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
            "vkGetQueryPoolResults (statistics)");
    result.patchTriangles = int64_t(primitives);
  } else if (!patches) {
    result.patchTriangles = 0;
  }
  if (settings.readImage && settings.draw) {
    result.rgba.resize(size_t(width_) * height_ * 4);
    std::memcpy(result.rgba.data(), imageReadback_.mapped, result.rgba.size());
  }
  if (settings.readDrawList) {
    uint32_t n = std::min(c.drawCount, drawCapacity_);
    const uint32_t* p = static_cast<const uint32_t*>(drawListReadback_.mapped);
    result.drawList.resize(n);
    for (uint32_t i = 0; i < n; i++) result.drawList[i] = {p[2 * i], p[2 * i + 1] & ~VGEO_DRAW_PATCHES_BIT};
  }
  if (profile) {
    const uint32_t* p = static_cast<const uint32_t*>(workerProfile_.mapped);
    result.workerProfile.assign(p, p + size_t(persistentWorkgroups_) * VGEO_PROFILE_WORKER_WORDS);
  }
}

// Whether the frame is complete; a traversal whose workers all ran out of iterations before the queue
// drained (lavapipe) gets twice the workers next frame (false then). A queue that did not drain for any
// other reason is a bug of the traversal and throws.
bool GpuRenderer::checkDrained(FrameResult& result) {
  const auto& c = result.counters;
  bool drained = c.itemsDone == c.queueWrite;
  result.complete =
      c.queueOverflow == 0 && c.drawOverflow == 0 && c.triangleOverflow == 0 && c.patchOverflow == 0 && drained;
  // Every worker left on its iteration budget (lavapipe) before the queue drained: twice as many for the
  // next frame, and a fresh queue (this one still holds items).
  result.workersRanOut = !drained && c.queueOverflow == 0 && c.budgetExits == persistentWorkgroups_ &&
                         persistentWorkgroups_ < kMaxPersistentWorkgroups;
  if (result.workersRanOut) {
    persistentWorkgroups_ = std::min(2 * persistentWorkgroups_, kMaxPersistentWorkgroups);
    setCapacities(queueCapacity_, drawCapacity_, triangleCapacity_, patchCapacity_);
    return false;
  }
  if (!drained && c.queueOverflow == 0)
    throw std::runtime_error("traversal did not drain its queue (" + std::to_string(c.itemsDone) + " of " +
                             std::to_string(c.queueWrite) + " items done, " + std::to_string(c.queueRead) +
                             " claimed; " + std::to_string(c.workgroupsExited) + " of " +
                             std::to_string(persistentWorkgroups_) + " workers left, " + std::to_string(c.budgetExits) +
                             " on their budget)");
  return true;
}

FrameResult GpuRenderer::renderFrame(const FrameSettings& settings) {
  const shaderio::FrameData frame = frameConstants(settings);
  std::memcpy(frameData_.mapped, &frame, sizeof(frame));
  const bool profile = settings.profileWorkers && persistentProfile_ && settings.traversal == Traversal::Persistent;
  prepareReadbacks(settings, profile);
  FrameResult result;
  result.culledInTraversal = frame.cullInTraversal != 0u;
  runPasses(settings, frame, result);
  readResults(settings, frame, profile, result);
  if (checkDrained(result)) growOverflowedLists(result.counters, settings.tau);
  return result;
}

}  // namespace vgeo
