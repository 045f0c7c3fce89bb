// gpu_renderer.h: the frame, all on the GPU (gpu_renderer.cpp; its passes recorded in frame_passes.cpp):
// instance culling, the traversal (persistent, per level or flat), triangle and patch culling, the compute
// rasterizers into the visibility buffer, the render pass (hardware triangles and patches), the resolve,
// and with occlusion culling all of it in two passes around the depth pyramid; read back once the frame
// is done. Targets and pipelines: gpu_pipelines.cpp; the growing lists: frame_lists.cpp.
#pragma once

#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "camera.h"
#include "occlusion_policy.h"
#include "reference_cut.h"
#include "scene.h"
#include "vulkan_context.h"

namespace vgeo {

enum class Traversal { Persistent, Levels, Flat };

// FrameSettings::sweepBudget unless set (docs/design.md, "The frame's passes": sweeps).
constexpr uint32_t kDefaultSweepBudget = 1u << 18;
// Triangle culling packs 64 clusters a workgroup (cull_small_clusters.comp) when the draw list's clusters
// average fewer triangles than this: far instances list roots of ~13 triangles, which leave most lanes of
// a workgroup a cluster idle (lavapipe pays for every lane and every workgroup: 3.8x, the H100 1.9x).
// Above it, one cluster a workgroup, whose loads are the same for every lane, is the faster
// (bench/README.md, "What the code's choices rest on").
constexpr uint32_t kDefaultPackedCullBelow = 32;

// Frames a run renders before it reads pass times (lists grown, shader caches and clocks warm): `vgeo
// render --frames` and the viewer's closing summary time the frames after these.
constexpr uint32_t kUntimedFrames = 5;

enum class InstanceCulling { Auto, Pass, InTraversal };

// Which rasterizer draws a listed triangle (shaderio_frame.h, VGEO_RASTER_*): Auto small ones in software
// where the device has 64-bit buffer atomics, Hardware all in the hardware draw, Software every one the
// software rasterizer can take (the rest, crossing the near plane or large, in hardware).
enum class Raster { Auto, Hardware, Software };

// What a frame's growing lists (queue, draw list, triangle list, patch list) may take together unless
// set otherwise (GpuRenderer::setFrameMemoryLimit): a cut that needs more stops the frame with a
// FrameMemoryError instead of growing without end (a tau of 1e-9 over a large scene asks for every leaf).
constexpr uint32_t kDefaultFrameMemoryMiB = 2048;
struct FrameMemoryError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
// A scene the device cannot hold (its arrays past the device's memory, or more instances than the
// queue's items can name), refused before anything is uploaded.
struct SceneTooLargeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct FrameSettings {
  View drawView;  // the picture
  View cullView;  // selection and culling (== drawView unless the cut is frozen)
  float tau = 1.0f;
  uint32_t mode = VGEO_MODE_LIT;
  Traversal traversal = Traversal::Persistent;
  bool readDrawList = false;  // copy the draw list back (tests, --compare-cpu)
  // Tests: FrameResult::pixelClusters, from the visibility buffer; the frame must draw every pixel into it
  // (FrameResult::drewIntoVisibility: Raster::Software, or auto on a GPU).
  bool readPixelClusters = false;
  bool readImage = true;
  bool draw = true;          // false: selection only (cut benchmarks); no image
  bool triangleCull = true;  // cull_triangles.comp before the draw (no change to the picture)
  bool patches = true;       // leaves too coarse for tau drawn as tessellated patches (needs triangleCull)
  uint32_t cullLanes = 0;    // lanes instance culling gives an instance: 0 the renderer's choice, else 1 or
                             // VGEO_CULL_INSTANCE_LANES (tests run both)
  // Where the persistent traversal's instances are culled: Auto is in its own dispatch (the workers cull
  // them first) on GPUs in scenes of up to 3 instances a worker, else in cull_instances.comp.
  InstanceCulling instanceCulling = InstanceCulling::Auto;
  // Persistent traversal: cluster tests a frame may spend sweeping whole simplification levels of an
  // instance (a run of clusters tested at once, one step) instead of walking their subtrees (a chain of
  // dependent steps); claimed level by level in instance culling until spent. 0: never sweep.
  uint32_t sweepBudget = kDefaultSweepBudget;
  Raster raster = Raster::Auto;  // with triangleCull
  // Triangle culling takes many clusters a workgroup when the draw list's clusters average fewer
  // triangles than this (0: never; tests force both ways).
  uint32_t packedCullBelow = kDefaultPackedCullBelow;
  // Two-pass occlusion culling (docs/design.md): what the last frame's depth does not hide first, then the
  // rest tested against the depth that drew. Auto runs two passes while they pay (occlusion_policy.h).
  // Frames that draw nothing, show overdraw or traverse by levels or flat run one pass. A frozen cut
  // (cullView != drawView) keeps the depth of the camera it froze at, and with it Auto runs two passes.
  Occlusion occlusion = Occlusion::Auto;
  glm::vec3 light{0.0f};  // the direction light comes from (the viewer's headlight); 0: the fixed light
  // The colour target's bytes in B, G, R, A order (the viewer copies them to a BGRA window; FrameResult's
  // rgba is R, G, B, A either way).
  bool bgraTarget = false;
  uint32_t pyramidViewLevel = 3;  // VGEO_MODE_PYRAMID: the level shown (clamped to 1 .. the top)
  bool profileWorkers = false;    // persistent traversal on a device with a shader device clock: record the
                                  // workers' iterations in FrameResult::workerProfile (benchmarks)
};

struct FrameResult {
  shaderio::Counters counters{};
  uint32_t trianglesDrawn = 0;          // sent to the rasterizers: after triangle culling, else the cut's triangles
  uint32_t softwareTriangles = 0;       // of those, drawn by the software rasterizer
  uint32_t patchesDrawn = 0;            // patches tessellated: by the hardware draw or the compute rasterizer
  uint32_t softwarePatches = 0;         // of those, drawn by the compute rasterizer
  int64_t patchTriangles = -1;          // triangles made of them (-1: no pipeline statistics for the hardware's)
  std::vector<CutEntry> drawList;       // when readDrawList
  std::vector<CutEntry> pixelClusters;  // when readPixelClusters in a render pass without attachments: the distinct
                                        // (instance, cluster) of the surfaces the picture shows
  std::vector<uint8_t> rgba;            // when readImage: width x height x 4
  bool culledInTraversal = false;       // the persistent traversal culled the instances (instanceCullMs: the reset)
  bool occlusion = false;               // two passes ran (counters: the frame's totals; drawBase the early pass's
                                        // clusters, occluded* what the late pass hid)
  bool pyramidBuilt = false;            // the frame left a depth pyramid (two passes, or one before a probe)
  bool drewIntoVisibility = false;      // the render pass had no attachments: every pixel from the visibility buffer
  // The passes' times: rasterMs the software rasterizer, drawMs the render pass (hardware draws), resolveMs
  // the shading of the software rasterizer's pixels; frameMs all of them and the read-back copies.
  // With occlusion culling each is the sum of both passes', and pyramidMs the depth pyramid's build.
  double instanceCullMs = 0.0, traversalMs = 0.0, triangleCullMs = 0.0, rasterMs = 0.0, drawMs = 0.0, resolveMs = 0.0,
         pyramidMs = 0.0, frameMs = 0.0;
  std::string timing;                   // "gpu-timestamps" or "host-per-submission"
  std::vector<uint32_t> workerProfile;  // when profiled: VGEO_PROFILE_WORKER_WORDS words a workgroup (shaderio.h)
  bool complete = true;                 // no overflow and the traversal drained its queue
  bool workersRanOut = false;           // not drained: every persistent worker left on its iteration budget
                                        // (lavapipe); the next frame runs twice as many
};

class GpuRenderer {
 public:
  // The shaders read the scene's arrays at their bindings, or by address when one passes what a binding
  // may hold or when `sceneByAddress` (tests compare the two).
  GpuRenderer(VulkanContext& context, const RenderScene& scene, uint32_t width, uint32_t height,
              bool sceneByAddress = false);
  ~GpuRenderer();
  GpuRenderer(const GpuRenderer&) = delete;
  GpuRenderer& operator=(const GpuRenderer&) = delete;

  // Renders one frame. Overflow of the queue or the draw list is reported in the result and grows the
  // buffers for the next frame.
  FrameResult renderFrame(const FrameSettings& settings);

  // The frame's colour target (RGBA8): after a frame in VK_IMAGE_LAYOUT_GENERAL, or in
  // TRANSFER_SRC_OPTIMAL when the frame read its image back (the viewer copies it to the window).
  VkImage colorImage() const { return color_; }
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  uint32_t queueCapacity() const { return queueCapacity_; }
  uint32_t drawCapacity() const { return drawCapacity_; }
  uint32_t triangleCapacity() const { return triangleCapacity_; }
  uint32_t patchCapacity() const { return patchCapacity_; }
  // Sets the capacities (tests use tiny ones to provoke overflow).
  void setCapacities(uint32_t queueItems, uint32_t drawEntries, uint32_t triangles, uint32_t patches);
  uint32_t persistentWorkgroups() const { return persistentWorkgroups_; }
  void setFrameMemoryLimit(uint64_t bytes) { frameMemoryLimit_ = bytes; }
  bool canProfileWorkers() const { return persistentProfile_ != VK_NULL_HANDLE; }
  // Whether the device runs the software rasterizer (64-bit buffer atomics, a picture one buffer holds).
  bool hasSoftwareRaster() const { return rasterSoftware_ != VK_NULL_HANDLE; }
  bool readsSceneByAddress() const { return sceneByAddress_; }
  // Overrides the persistent traversal's workgroup count (benchmarks; the default is what the device
  // runs at once).
  void setPersistentWorkgroups(uint32_t count) { persistentWorkgroups_ = std::max(count, 1u); }
  // Loop iterations after which a persistent worker leaves (lavapipe only; tests make it tiny).
  void setIterationBudget(uint32_t iterations) {
    if (iterationBudget_ != 0) iterationBudget_ = std::max(iterations, 1u);
  }
  // Whether the persistent traversal culls the instances itself (FrameSettings::instanceCulling), with
  // VGEO_CULL_INSTANCE_LANES lanes an instance: never with cullLanes 1; Auto on GPUs, in scenes of up to
  // kCullInTraversalPerWorker instances a worker, where it beat the culling pass (bench/README.md, cut
  // selection). InTraversal up to kCullInTraversalMaxPerWorker a worker: lavapipe
  // counts the culling's loop iterations (~50 an instance at most) against its limit of 65,535 an
  // invocation, past the traversal's budget (kLavapipeIterationBudget), which leaves ~15,000 to spare.
  static constexpr size_t kCullInTraversalPerWorker = 3, kCullInTraversalMaxPerWorker = 64;
  bool cullsInTraversal(const FrameSettings& s) const {
    const size_t instances = scene_.data.instances.size();
    if (s.traversal != Traversal::Persistent || s.instanceCulling == InstanceCulling::Pass || s.cullLanes == 1)
      return false;
    if (s.instanceCulling == InstanceCulling::InTraversal)
      return instances <= kCullInTraversalMaxPerWorker * persistentWorkgroups_;
    return claimMode_ == VGEO_CLAIM_PAST_FRONTIER && cullInstanceLanes(s) != 1 &&
           instances <= kCullInTraversalPerWorker * persistentWorkgroups_;
  }

 private:
  void createTargets();
  void createPipelines(bool softwareRaster);
  void createDescriptorSet();
  void createComputePipelines(bool softwareRaster);
  void createDrawPipelines();
  void createQueueAndDrawList();
  void writeDescriptors();
  // renderFrame's steps, in order (gpu_renderer.cpp).
  OcclusionPlan occlusionPlan(const FrameSettings& settings) const;
  shaderio::FrameData frameConstants(const FrameSettings& settings, OcclusionPlan plan) const;
  void prepareReadbacks(const FrameSettings& settings, bool profile);
  void runPasses(const FrameSettings& settings, const shaderio::FrameData& frame, OcclusionPlan plan,
                 bool intoVisibility, FrameResult& result);
  void readResults(const FrameSettings& settings, const shaderio::FrameData& frame, bool profile, bool intoVisibility,
                   FrameResult& result);
  bool checkDrained(FrameResult& result);
  void growOverflowedLists(const shaderio::Counters& counters, float tau);
  void recordCounterReset(VkCommandBuffer cmd, uint32_t nodesPending = 0);
  // The stages that see the descriptor set and the push constants.
  VkShaderStageFlags rendererStages() const {
    return VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT |
           (vk_.tessellation() ? VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT | VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT
                               : 0u);
  }
  // Sets the push constants (shaderio_frame.h, PassConstants) that every pass's shaders read.
  void pushPass(VkCommandBuffer cmd, uint32_t pass);
  // 1.-2. The counters reset (the late pass: begin_late_pass.glsl instead), then instance culling.
  void recordInstanceCull(VkCommandBuffer cmd, const FrameSettings& settings, uint32_t pass);
  // Lanes that cull one instance: VGEO_CULL_INSTANCE_LANES test a root's children side by side (a shorter
  // chain in front of the traversal of a small scene); in large scenes one, as the reservations of many
  // more workgroups on one counter cost more than that; on lavapipe one (a CPU's SIMD lanes gain nothing
  // from the spread).
  uint32_t cullInstanceLanes(const FrameSettings& settings) const {
    if (settings.cullLanes != 0) return settings.cullLanes == 1 ? 1 : VGEO_CULL_INSTANCE_LANES;
    return !vk_.isLavapipe() && scene_.data.instances.size() <= VGEO_CULL_SPREAD_INSTANCES ? VGEO_CULL_INSTANCE_LANES
                                                                                           : 1;
  }
  // Instances a workgroup of cull_instances.comp culls: 64 in its serial variant (one lane each), else
  // VGEO_CULL_SPREAD_WORKGROUP / VGEO_CULL_INSTANCE_LANES.
  uint32_t cullInstancesPerWorkgroup(const FrameSettings& settings) const {
    return cullInstanceLanes(settings) == 1 ? VGEO_CULL_SERIAL_WORKGROUP
                                            : VGEO_CULL_SPREAD_WORKGROUP / VGEO_CULL_INSTANCE_LANES;
  }
  void recordTraversal(VkCommandBuffer cmd, const FrameSettings& settings, uint32_t pass);
  void recordTriangleCull(VkCommandBuffer cmd, bool patches);
  void recordSoftwareRaster(VkCommandBuffer cmd, bool patches, bool clear);
  void recordRenderPass(VkCommandBuffer cmd, const FrameSettings& settings, bool intoVisibility, uint32_t pass);
  void recordDepthPyramid(VkCommandBuffer cmd);
  // The pyramid levels a workgroup's tile reduces to in shared memory (build_depth_pyramid.comp): 1 on
  // lavapipe, where each of the tile's barriers costs more than the one workgroup's work above it.
  uint32_t pyramidTileLevels() const { return vk_.isLavapipe() ? 1u : 5u; }
  // Whether a frame with these settings may cull by occlusion (two passes): it must draw, the overdraw view
  // shows every layer (its compute rasterizers count instead of keeping depth), and the late pass's first
  // items may be clusters (runs of one), which only the persistent traversal takes.
  bool mayOcclude(const FrameSettings& s) const {
    return s.occlusion != Occlusion::Off && s.draw && s.mode != VGEO_MODE_OVERDRAW &&
           s.traversal == Traversal::Persistent;
  }
  // Whether a frame culled by occlusion keeps the depth pyramid it has (a frozen cut: both passes test
  // against the pyramid of the camera it froze at) instead of building one between its passes.
  // Views compare by their bits, so that the two questions below are each other's negation for any view.
  static bool sameView(const View& a, const View& b) {
    return std::memcmp(&a.viewProjection, &b.viewProjection, sizeof(a.viewProjection)) == 0;
  }
  static bool keepsPyramid(const FrameSettings& s) { return !sameView(s.cullView, s.drawView); }
  // Whether the depth pyramid was drawn from this camera: a frozen cut needs it from the camera it froze at.
  bool pyramidDrawnFrom(const View& view) const { return pyramidMade_ && sameView(pyramidView_, view); }
  void recordResolve(VkCommandBuffer cmd, uint32_t mode, bool patches, bool intoVisibility);
  Pipeline computePipeline(const uint32_t* code, size_t bytes, const VkSpecializationInfo* specialization = nullptr);
  VkPipeline resolvePipeline(uint32_t mode, bool patches, bool everyPixel);
  void recordReadback(VkCommandBuffer cmd, const FrameSettings& settings);
  VkPipelineStageFlags drawShaderStages() const;
  // Whether a frame with these settings draws leaves as patches (the patch list is made by triangle culling).
  bool drawsPatches(const FrameSettings& s) const {
    return s.draw && s.triangleCull && s.patches && drawPatches_ != VK_NULL_HANDLE && !scene_.data.patches.empty();
  }
  // The frame's VGEO_RASTER_* (triangle culling bins the triangles).
  uint32_t softwareRaster(const FrameSettings& s) const {
    if (!s.draw || !s.triangleCull || rasterSoftware_ == VK_NULL_HANDLE || s.raster == Raster::Hardware)
      return VGEO_RASTER_NONE;
    return s.raster == Raster::Software ? VGEO_RASTER_ALL : VGEO_RASTER_SMALL;
  }
  // Whether the frame's render pass is the one without attachments (no attachments): its triangles (and the patches the
  // compute rasterizer leaves to the hardware, from their grids) go into the visibility buffer and the
  // resolve shades every pixel. Not when patches go to the tessellator: it draws with depth.
  bool drawsIntoVisibility(const FrameSettings& s, const shaderio::FrameData& frame) const {
    return s.draw && frame.softwareRaster != VGEO_RASTER_NONE && drawVisibility_ != VK_NULL_HANDLE &&
           (frame.drawPatches == 0u || frame.softwarePatches != 0u);
  }
  // Whether patch culling bins patches to the compute rasterizer too. Not by default on lavapipe: it runs
  // every line of a shader whatever its lanes branch to (docs/gpu-notes.md, 17), so each grid point there
  // pays for every kind of patch evaluation; its tessellator is the faster path.
  bool rastersPatchesInCompute(const FrameSettings& s) const {
    return drawsPatches(s) && softwareRaster(s) != VGEO_RASTER_NONE && vk_.drawIndirectCount() &&
           (s.raster == Raster::Software || !vk_.isLavapipe());
  }

  VulkanContext& vk_;
  const RenderScene& scene_;
  uint32_t width_, height_;
  uint32_t queueCapacity_ = 1u << 20, drawCapacity_ = 1u << 20, triangleCapacity_ = 1u << 22, patchCapacity_ = 1u << 18;
  uint32_t patchGridCapacity_ = 1;
  uint32_t persistentWorkgroups_ = 0, iterationBudget_ = 0;
  uint32_t claimMode_ = VGEO_CLAIM_PAST_FRONTIER;  // VGEO_CLAIM_WRITTEN on lavapipe
  uint32_t lastCullItems_ = 0;  // the last frame's counters.cullItems: sizes the persistent traversal's first claim
  uint64_t frameMemoryLimit_ = uint64_t(kDefaultFrameMemoryMiB) << 20;

  Buffer visibilityReadback_, patchListReadback_;  // host-visible, made when first asked for
  Buffer frameData_, counters_, countersReadback_, queue_, drawList_, drawListReadback_, imageReadback_, triangleList_,
      patchList_, patchDraws_, patchEntries_, visibility_, overdraw_, patchGrid_,
      depthPyramid_,       // built from what the early pass drew (build_depth_pyramid.comp)
      deferredInstances_,  // the instances the early pass left to the late one (a word each)
      deferredItems_,      // queue items the early pass left to the late one (the queue's capacity)
      workerProfile_;      // host-visible; a placeholder until a frame is profiled
  std::vector<std::pair<uint32_t, Buffer>> sceneBuffers_;  // the scene's arrays, uploaded once, by binding
  Buffer sceneArrays_;                                     // their addresses (VGEO_BINDING_SCENE)
  bool sceneByAddress_ = false;  // an array passes maxStorageBufferRange: the shaders' by-address variant
  uint32_t pyramidLevels_ = 0;
  uint32_t pyramidOffsets_[VGEO_PYRAMID_MAX_LEVELS] = {};
  bool pyramidMade_ = false;  // depthPyramid_ holds a picture, drawn from pyramidView_
  View pyramidView_;
  OcclusionPolicy occlusionPolicy_;  // Occlusion::Auto's frames
  VkImage color_ = VK_NULL_HANDLE, depth_ = VK_NULL_HANDLE;
  VkDeviceMemory colorMemory_ = VK_NULL_HANDLE, depthMemory_ = VK_NULL_HANDLE;
  VkImageView colorView_ = VK_NULL_HANDLE, depthView_ = VK_NULL_HANDLE;
  VkRenderPass renderPass_ = VK_NULL_HANDLE, renderPassResolved_ = VK_NULL_HANDLE,
               renderPassLoad_ = VK_NULL_HANDLE,  // the late pass's: keeps what the early pass drew
      renderPassVisibility_ = VK_NULL_HANDLE;     // no attachments: draw_visibility.frag
  VkFramebuffer framebuffer_ = VK_NULL_HANDLE, framebufferVisibility_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkDescriptorPool descriptorPool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  // Instance culling and the persistent traversal, [0] without the occlusion tests, [1] with them.
  Pipeline cull_[2], cullSerial_[2], persistent_[2];
  Pipeline persistentProfile_, level_, prepareLevel_, flat_, prepareFlat_, resetFlat_, finalize_, draw_, cullTriangles_,
      cullSmallClusters_, preparePatches_, cullPatches_, finalizeTriangles_, drawOverdraw_, drawPatches_,
      drawPatchesOverdraw_, rasterSoftware_, rasterPatches_, drawVisibility_, drawGridVisibility_, buildDepthPyramid_,
      beginLatePass_, queueDeferred_;
  // resolve.comp, one pipeline a view, made when first used (a shader with only its view's code: lavapipe
  // runs every line of a shader whatever branch its lanes take, docs/gpu-notes.md 17).
  // [view][whether patches are in the visibility buffer][whether every pixel is (no render-pass attachments)]
  Pipeline resolve_[VGEO_MODE_COUNT][2][2];
  VkSampler depthSampler_ = VK_NULL_HANDLE;
  VkQueryPool queries_ = VK_NULL_HANDLE;
  VkQueryPool statistics_ = VK_NULL_HANDLE;  // clipping invocations of the patch draw (its triangles)
};

const char* traversalName(Traversal t);

// Binding count of the one descriptor set (shaderio.h, VGEO_BINDING_*).
constexpr uint32_t kRendererBindings = VGEO_BINDING_COUNT;
inline VkDescriptorType descriptorType(uint32_t binding) {
  return binding == VGEO_BINDING_SCENE         ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER
         : binding == VGEO_BINDING_COLOR_IMAGE ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE
         : binding == VGEO_BINDING_DEPTH_IMAGE ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER
                                               : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
}

}  // namespace vgeo
