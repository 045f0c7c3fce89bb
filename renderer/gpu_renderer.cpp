// gpu_renderer.cpp: the frame. renderFrame() is its steps: the frame's constants, its passes recorded and
// timed in order by runPasses() (each pass in frame_passes.cpp), the results read back, and the lists
// that overflowed grown for the next frame. Also the scene's buffers and the descriptor set. No host
// read-back happens inside the frame.
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
// Frame start, then the end of each pass of runPasses (at most 13: two selections of five, the depth
// pyramid, the resolve and the copies back).
constexpr uint32_t kMaxTimestamps = 16;

double msSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

const char* traversalName(Traversal t) {
  return t == Traversal::Persistent ? "persistent" : t == Traversal::Levels ? "levels" : "flat";
}

GpuRenderer::GpuRenderer(VulkanContext& context, const RenderScene& scene, uint32_t width, uint32_t height,
                         bool sceneByAddress)
    : vk_(context), scene_(scene), width_(width), height_(height), sceneByAddress_(sceneByAddress) {
  const VgeoData& d = scene.data;
  VkDeviceSize range = vk_.properties().limits.maxStorageBufferRange;
  // The scene's arrays, each uploaded once; the shaders read them at their bindings or, when one passes
  // what a binding may hold, by address (shaderio_frame.h, SceneArrays; common.glsl).
  auto bytes = [](const auto& v) { return v.size() * sizeof(v[0]); };
  shaderio::SceneArrays addresses{};
  struct SceneArray {
    uint32_t binding;
    glm::uvec2* address;
    const void* data;
    size_t bytes;
  } sections[] = {
#define VGEO_SCENE_ARRAY_UPLOAD(binding, array, type, align, owner) \
  {binding, &addresses.array, owner.array.data(), bytes(owner.array)},
      VGEO_SCENE_ARRAYS(VGEO_SCENE_ARRAY_UPLOAD)
#undef VGEO_SCENE_ARRAY_UPLOAD
  };
  // Sweep runs carry their length above the instance index (shaderio.h, VGEO_ITEM_RUN_BIT).
  if (d.instances.size() >= (size_t(1) << VGEO_RUN_INSTANCE_BITS))
    throw SceneTooLargeError("scene too large: " + std::to_string(d.instances.size()) + " instances (at most " +
                             std::to_string((1u << VGEO_RUN_INSTANCE_BITS) - 1) + ")");
  // Refused before any upload when the arrays alone exceed the device's memory.
  uint64_t sceneBytes = 0;
  for (const auto& s : sections) sceneBytes += s.bytes;
  if (sceneBytes > vk_.deviceLocalBytes())
    throw SceneTooLargeError("scene too large for this device: its arrays need " + std::to_string(sceneBytes >> 20) +
                             " MiB, the device's memory is " + std::to_string(vk_.deviceLocalBytes() >> 20) + " MiB");
  for (const auto& s : sections) sceneByAddress_ = sceneByAddress_ || s.bytes > range;
  for (const auto& s : sections) {
    sceneBuffers_.push_back({s.binding, vk_.createBuffer(s.bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                                                      VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT)});
    const Buffer& b = sceneBuffers_.back().second;
    vk_.upload(b, s.data, s.bytes);
    const VkDeviceAddress address = vk_.deviceAddress(b);
    *s.address = glm::uvec2(uint32_t(address), uint32_t(address >> 32));
  }
  sceneArrays_ = vk_.createBuffer(sizeof(addresses), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  vk_.upload(sceneArrays_, &addresses, sizeof(addresses));
  frameData_ = vk_.createBuffer(sizeof(shaderio::FrameData), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
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
  // The compute-rasterized patches' grid points, as many as a grid word can address (16 MiB); patches
  // past it go to the tessellator.
  patchGridCapacity_ = software && vk_.tessellation() && !d.patches.empty() ? 1u << VGEO_PATCH_GRID_OFFSET_BITS : 1u;
  patchGrid_ = vk_.createBuffer(VkDeviceSize(patchGridCapacity_) * 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  // Occlusion culling: the depth pyramid's levels up to one texel (level 0, the pixels, is not stored:
  // build_depth_pyramid.comp), and the list of deferred instances.
  uint32_t pyramidFloats = 0;
  for (uint32_t w = width_, h = height_;; w = (w + 1) / 2, h = (h + 1) / 2) {
    if (pyramidLevels_ == VGEO_PYRAMID_MAX_LEVELS) throw std::runtime_error("picture too large for the depth pyramid");
    pyramidOffsets_[pyramidLevels_] = pyramidFloats;
    if (pyramidLevels_++ > 0) pyramidFloats += w * h;
    if (pyramidLevels_ > 1 && w == 1 && h == 1) break;
  }
  depthPyramid_ = vk_.createBuffer(VkDeviceSize(pyramidFloats) * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  deferredInstances_ = vk_.createBuffer(std::max<VkDeviceSize>(VkDeviceSize(d.instances.size()) * 4, 16),
                                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);

  if (vk_.isLavapipe()) {
    claimMode_ = VGEO_CLAIM_WRITTEN;
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
    pushPass(cmd, VGEO_PASS_ONLY);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, persistent_[0]);
    vkCmdDispatch(cmd, persistentWorkgroups_, 1, 1);
    vk_.submitAndWait(cmd);
  }
  VkQueryPoolCreateInfo q{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  q.queryType = VK_QUERY_TYPE_TIMESTAMP;
  q.queryCount = kMaxTimestamps;
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
  // The pipelines and buffers destroy themselves (Pipeline, Buffer), after this body.
  vkDestroyPipelineLayout(dev, layout_, nullptr);
  vkDestroyDescriptorPool(dev, descriptorPool_, nullptr);
  vkDestroyDescriptorSetLayout(dev, setLayout_, nullptr);
  vkDestroyQueryPool(dev, queries_, nullptr);
  if (statistics_) vkDestroyQueryPool(dev, statistics_, nullptr);
  vkDestroySampler(dev, depthSampler_, nullptr);
  vkDestroyFramebuffer(dev, framebuffer_, nullptr);
  vkDestroyFramebuffer(dev, framebufferVisibility_, nullptr);
  vkDestroyRenderPass(dev, renderPassVisibility_, nullptr);
  vkDestroyRenderPass(dev, renderPass_, nullptr);
  vkDestroyRenderPass(dev, renderPassResolved_, nullptr);
  vkDestroyRenderPass(dev, renderPassLoad_, nullptr);
  vkDestroyImageView(dev, colorView_, nullptr);
  vkDestroyImageView(dev, depthView_, nullptr);
  vkDestroyImage(dev, color_, nullptr);
  vkDestroyImage(dev, depth_, nullptr);
  vkFreeMemory(dev, colorMemory_, nullptr);
  vkFreeMemory(dev, depthMemory_, nullptr);
}

void GpuRenderer::writeDescriptors() {
  const VkDeviceSize range = vk_.properties().limits.maxStorageBufferRange;
  const Buffer* buffers[kRendererBindings] = {};
  buffers[VGEO_BINDING_FRAME] = &frameData_;
  buffers[VGEO_BINDING_SCENE] = &sceneArrays_;
  buffers[VGEO_BINDING_COUNTERS] = &counters_;
  buffers[VGEO_BINDING_QUEUE] = &queue_;
  buffers[VGEO_BINDING_DRAW_LIST] = &drawList_;
  buffers[VGEO_BINDING_TRIANGLE_LIST] = &triangleList_;
  buffers[VGEO_BINDING_PATCH_LIST] = &patchList_;
  buffers[VGEO_BINDING_PATCH_DRAWS] = &patchDraws_;
  buffers[VGEO_BINDING_PATCH_ENTRIES] = &patchEntries_;
  buffers[VGEO_BINDING_WORKER_PROFILE] = &workerProfile_;
  buffers[VGEO_BINDING_VISIBILITY] = &visibility_;
  buffers[VGEO_BINDING_OVERDRAW] = &overdraw_;
  buffers[VGEO_BINDING_PATCH_GRID] = &patchGrid_;
  buffers[VGEO_BINDING_DEPTH_PYRAMID] = &depthPyramid_;
  buffers[VGEO_BINDING_DEFERRED_INSTANCES] = &deferredInstances_;
  buffers[VGEO_BINDING_DEFERRED_ITEMS] = &deferredItems_;
  for (const auto& [binding, b] : sceneBuffers_) {
    if (buffers[binding]) throw std::logic_error("binding " + std::to_string(binding) + " taken twice");
    buffers[binding] = &b;
  }
  const VkDescriptorImageInfo colorImage{VK_NULL_HANDLE, colorView_, VK_IMAGE_LAYOUT_GENERAL},
      depthImage{depthSampler_, depthView_, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL};
  VkDescriptorBufferInfo infos[kRendererBindings];
  VkWriteDescriptorSet writes[kRendererBindings];
  for (uint32_t i = 0; i < kRendererBindings; i++) {
    const VkDescriptorType type = descriptorType(i);
    const bool image = type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE || type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    if (!image && !buffers[i]) throw std::logic_error("binding " + std::to_string(i) + " has no buffer");
    // An array past a binding's range is read by address; its binding shows what fits (unused).
    if (!image) infos[i] = {buffers[i]->buffer, 0, std::min<VkDeviceSize>(buffers[i]->size, range)};
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

// How a frame with these settings runs: one pass, or two culling by occlusion (always with On and for a
// frozen cut, with Auto as the policy says).
OcclusionPlan GpuRenderer::occlusionPlan(const FrameSettings& settings) const {
  if (!mayOcclude(settings)) return OcclusionPlan::OnePass;
  if (settings.occlusion == Occlusion::On || keepsPyramid(settings)) return OcclusionPlan::TwoPass;
  const OcclusionPlan plan = occlusionPolicy_.next(pyramidMade_);
  // The pyramid view shows this frame's pyramid: a one-pass frame builds one.
  return plan == OcclusionPlan::OnePass && settings.mode == VGEO_MODE_PYRAMID ? OcclusionPlan::OnePassThenPyramid
                                                                              : plan;
}

// The frame's constants (shaderio.h, FrameData) for these settings.
shaderio::FrameData GpuRenderer::frameConstants(const FrameSettings& settings, OcclusionPlan plan) const {
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
  frame.drawPatches = drawsPatches(settings) ? 1u : 0u;
  frame.patchesPerInstance = vk_.isLavapipe() ? kLavapipePatchesPerInstance : kPatchesPerInstance;
  frame.patchCapacity = patchCapacity_;
  frame.softwareRaster = softwareRaster(settings);
  frame.softwarePatches = rastersPatchesInCompute(settings) ? 1u : 0u;
  frame.patchGridCapacity = patchGridCapacity_;
  frame.packedCullBelow = settings.packedCullBelow;
  // Occlusion culling: the early pass tests against the pyramid the last frame left (none: it tests
  // nothing), from the camera it was drawn from; the late pass against the one built in between, from this
  // frame's camera. A frozen cut keeps the pyramid of the camera it froze at, for both.
  if (plan == OcclusionPlan::TwoPass) {
    const bool frozen = keepsPyramid(settings);
    frame.occlusion = frozen ? VGEO_OCCLUSION_FROZEN : VGEO_OCCLUSION_ON;
    frame.earlyOcclusion = pyramidMade_ ? 1u : 0u;
    const View& late = frozen ? pyramidView_ : settings.cullView;
    frame.pyramidViews[0] = pyramidView_.view;
    frame.pyramidViews[1] = late.view;
    frame.pyramidProjections = glm::vec4(pyramidView_.projection, late.projection);
    frame.pyramidZnear = glm::vec2(pyramidView_.znear, late.znear);
  }
  frame.pyramidLevels = pyramidLevels_;
  frame.pyramidTileLevels = pyramidTileLevels();
  frame.cullInstancesPerWorkgroup = cullInstancesPerWorkgroup(settings);
  frame.lodLevels = scene_.maxLevels;
  frame.bgraTarget = settings.bgraTarget ? 1u : 0u;
  frame.pyramidViewLevel = std::clamp(settings.pyramidViewLevel, 1u, std::max(pyramidLevels_, 2u) - 1u);
  if (glm::length(settings.light) > 0.0f) frame.light = glm::vec4(glm::normalize(settings.light), 1.0f);
  frame.persistentWorkgroups = persistentWorkgroups_;
  for (uint32_t i = 0; i < pyramidLevels_; i++) frame.pyramidOffsets[i / 4][i % 4] = pyramidOffsets_[i];
  return frame;
}

// Records and submits the passes in frame order and times each: GPU timestamps in one submission, or on
// lavapipe one submission a pass timed on the host. With occlusion culling the selection and drawing run
// twice (docs/design.md, "Occlusion culling"), the depth pyramid between.
void GpuRenderer::runPasses(const FrameSettings& settings, const shaderio::FrameData& frame, OcclusionPlan plan,
                            bool intoVisibility, FrameResult& result) {
  // The frame's passes in order, each with where its time goes (nullptr: the frame's only) and the
  // selection pass it belongs to (VGEO_PASS_*).
  const bool software = frame.softwareRaster != VGEO_RASTER_NONE;
  struct Pass {
    double* ms;
    uint32_t pass;
    std::function<void(VkCommandBuffer)> record;
  };
  std::vector<Pass> passes;
  // Patches are culled and drawn once, in the last pass (the early one lists their entries).
  auto addSelection = [&](uint32_t pass) {
    const bool patches = frame.drawPatches != 0u && pass != VGEO_PASS_EARLY,
               softwarePatches = frame.softwarePatches != 0u && pass != VGEO_PASS_EARLY;
    passes.push_back(
        {&result.instanceCullMs, pass, [&, pass](VkCommandBuffer cmd) { recordInstanceCull(cmd, settings, pass); }});
    passes.push_back(
        {&result.traversalMs, pass, [&, pass](VkCommandBuffer cmd) { recordTraversal(cmd, settings, pass); }});
    if (frame.triangleCull != 0u)
      passes.push_back(
          {&result.triangleCullMs, pass, [this, patches](VkCommandBuffer cmd) { recordTriangleCull(cmd, patches); }});
    if (software)
      passes.push_back({&result.rasterMs, pass, [this, softwarePatches, pass](VkCommandBuffer cmd) {
                          recordSoftwareRaster(cmd, softwarePatches, pass != VGEO_PASS_LATE);
                        }});
    if (settings.draw)
      passes.push_back({&result.drawMs, pass, [&, intoVisibility, pass](VkCommandBuffer cmd) {
                          recordRenderPass(cmd, settings, intoVisibility, pass);
                        }});
  };
  if (frame.occlusion == VGEO_OCCLUSION_OFF) {
    addSelection(VGEO_PASS_ONLY);
    if (plan == OcclusionPlan::OnePassThenPyramid)  // for the next frame, a probe (occlusion_policy.h)
      passes.push_back({&result.pyramidMs, VGEO_PASS_ONLY, [this](VkCommandBuffer cmd) { recordDepthPyramid(cmd); }});
  } else {
    addSelection(VGEO_PASS_EARLY);
    if (frame.occlusion == VGEO_OCCLUSION_ON)  // a frozen cut keeps the pyramid it froze with
      passes.push_back({&result.pyramidMs, VGEO_PASS_EARLY, [this](VkCommandBuffer cmd) { recordDepthPyramid(cmd); }});
    addSelection(VGEO_PASS_LATE);
  }
  if (settings.draw && (software || settings.mode == VGEO_MODE_PYRAMID))  // the pyramid view: every pixel
    passes.push_back({&result.resolveMs, VGEO_PASS_LATE, [&](VkCommandBuffer cmd) {
                        recordResolve(cmd, settings.mode, frame.softwarePatches != 0u, intoVisibility);
                      }});
  passes.push_back({nullptr, VGEO_PASS_LATE, [&](VkCommandBuffer cmd) { recordReadback(cmd, settings); }});
  if (passes.size() + 1 > kMaxTimestamps) throw std::logic_error("more passes than timestamps");
  const double period = vk_.timestampPeriod();
  const auto start = std::chrono::steady_clock::now();
  if (vk_.isLavapipe() || period == 0.0) {
    // lavapipe's compute timestamps are wrong after the first submission (docs/gpu-notes.md, 3): one submission
    // a pass, timed on the host.
    result.timing = "host-per-submission";
    for (const Pass& pass : passes) {
      const auto passStart = std::chrono::steady_clock::now();
      VkCommandBuffer cmd = vk_.beginCommands();
      pushPass(cmd, pass.pass);
      pass.record(cmd);
      vk_.submitAndWait(cmd);
      if (pass.ms) *pass.ms += msSince(passStart);
    }
    result.frameMs = msSince(start);
  } else {
    result.timing = "gpu-timestamps";
    VkCommandBuffer cmd = vk_.beginCommands();
    const uint32_t stamps = uint32_t(passes.size()) + 1;
    vkCmdResetQueryPool(cmd, queries_, 0, stamps);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries_, 0);
    for (uint32_t i = 0; i < passes.size(); i++) {
      pushPass(cmd, passes[i].pass);
      passes[i].record(cmd);
      vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, i + 1);
    }
    vk_.submitAndWait(cmd);
    uint64_t t[kMaxTimestamps];
    vkCheck(vkGetQueryPoolResults(vk_.device(), queries_, 0, stamps, stamps * sizeof(uint64_t), t, sizeof(uint64_t),
                                  VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
            "vkGetQueryPoolResults");
    auto ms = [&](uint32_t from, uint32_t to) { return double(t[to] - t[from]) * period * 1e-6; };
    for (uint32_t i = 0; i < passes.size(); i++)
      if (passes[i].ms) *passes[i].ms += ms(i, i + 1);
    result.frameMs = ms(0, stamps - 1);
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
  const bool ranOut = c.budgetExits - c.earlyBudgetExits == persistentWorkgroups_ ||
                      c.earlyBudgetExits == persistentWorkgroups_;  // in either pass
  result.workersRanOut = !drained && c.queueOverflow == 0 && ranOut && persistentWorkgroups_ < kMaxPersistentWorkgroups;
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
  if (!finiteView(settings.drawView) || !finiteView(settings.cullView))
    throw std::invalid_argument("the camera's view is not finite in float (eye too far, or field of view too narrow)");
  const OcclusionPlan plan = occlusionPlan(settings);
  shaderio::FrameData frame = frameConstants(settings, plan);
  if (frame.occlusion == VGEO_OCCLUSION_FROZEN && !pyramidDrawnFrom(settings.cullView)) {
    // A cut frozen at a camera this renderer has not drawn from: a frame from it first, as a viewer would
    // have drawn before freezing, leaves its pyramid.
    FrameSettings from = settings;
    from.drawView = settings.cullView;
    from.occlusion = Occlusion::On;
    from.readImage = from.readDrawList = from.profileWorkers = false;
    renderFrame(from);
    frame = frameConstants(settings, plan);
  }
  const bool profile = settings.profileWorkers && persistentProfile_ && settings.traversal == Traversal::Persistent;
  prepareReadbacks(settings, profile);
  FrameResult result;
  result.culledInTraversal = frame.cullInTraversal != 0u;
  result.occlusion = frame.occlusion != VGEO_OCCLUSION_OFF;
  const bool intoVisibility = drawsIntoVisibility(settings, frame);
  frame.pyramidSources = intoVisibility
                             ? VGEO_PYRAMID_FROM_VISIBILITY
                             : VGEO_PYRAMID_FROM_DEPTH_IMAGE |
                                   (frame.softwareRaster != VGEO_RASTER_NONE ? VGEO_PYRAMID_FROM_VISIBILITY : 0u);
  std::memcpy(frameData_.mapped, &frame, sizeof(frame));
  runPasses(settings, frame, plan, intoVisibility, result);
  readResults(settings, frame, profile, intoVisibility, result);
  result.drewIntoVisibility = intoVisibility;
  result.pyramidBuilt = frame.occlusion == VGEO_OCCLUSION_ON || plan == OcclusionPlan::OnePassThenPyramid;
  if (result.pyramidBuilt) {  // the next frame's early pass tests against this pyramid
    pyramidMade_ = true;
    pyramidView_ = settings.cullView;
  }
  if (checkDrained(result)) growOverflowedLists(result.counters, settings.tau);
  // An incomplete frame's time says nothing of either way (it is drawn again, with larger lists).
  if (settings.occlusion == Occlusion::Auto && frame.occlusion != VGEO_OCCLUSION_FROZEN && mayOcclude(settings) &&
      result.complete)
    occlusionPolicy_.record(plan, result.frameMs, result.pyramidMs);
  return result;
}

}  // namespace vgeo
