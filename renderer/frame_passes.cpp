// frame_passes.cpp: the frame's passes, each recorded into a command buffer, in frame order
// (GpuRenderer::runPasses records and times them):
//   1. counter reset             (transfer)
//   2. cull_instances.comp       1 or 64 lanes an instance (64 on GPUs up to 4,096 instances) -> queue of
//                                (instance, level subtree root), or of (instance, BVH root) for flat; in
//                                scenes of up to 3 instances a persistent worker on GPUs, the workers cull
//                                them first themselves (cull_instances.glsl), in the traversal's dispatch
//   3. traversal                 persistent: one dispatch of resident workgroups draining the queue
//                                levels: per depth, prepare_level.comp then traverse_level.comp (indirect)
//                                flat: prepare_flat.comp then traverse_flat.comp (one thread a cluster)
//   4. draw_arguments.glsl       triangle-culling dispatch (or draw) arguments from the draw-list count:
//                                the persistent traversal's last worker, reset_flat.comp, finalize.comp
//   5. cull_triangles.comp       one workgroup a listed cluster -> triangle list, binned to the software
//                                rasterizer or the hardware; patch-drawn clusters -> patch-entry list
//      cull_small_clusters.comp  the same, 64 listed clusters a workgroup, when the frame's are small
//      prepare_patches.comp,     with patches: one workgroup a patch-drawn cluster -> patch list,
//      cull_patches.comp         binned to the compute rasterizer or the tessellator
//      finalize_triangles.comp   the draws' and the software rasterizer's indirect arguments
//   6. raster_software.comp      the small triangles into the visibility buffer
//      raster_patches.comp       the patches binned to compute: tessellated and rasterized there
//   7. render pass               one vkCmdDrawIndirect of the hardware's triangles (draw.vert; without
//                                triangle culling, of 384 vertices x listed clusters): into the
//                                visibility buffer in a pass without attachments (draw_visibility.frag),
//                                with the patch grids left to the hardware (patch_grid.vert, a draw
//                                each); or shaded with depth (draw.frag) and then one draw of the
//                                tessellator's patches, one vertex a patch (patch.vert, .tesc, .tese)
//   With occlusion culling 2. to 7. are the early pass (no patches), and then
//      build_depth_pyramid.comp  the depth pyramid of what it drew, its last workgroup beginning the late
//                                pass (begin_late_pass.glsl: the late pass's counters; a frozen cut, which
//                                keeps its pyramid, runs begin_late_pass.comp instead)
//      then 2. to 7. again, tested against the pyramid, instance culling first queueing the items the
//      early pass deferred (queue_deferred.glsl; queue_deferred.comp where the traversal culls instances)
//   8. resolve.comp              the compute rasterizers' pixels shaded into the colour target
//   9. copies back               counters (and the image / draw list when asked; frame_readback.cpp)
#include "gpu_renderer.h"

namespace vgeo {
namespace {

void computeToCompute(VkCommandBuffer cmd) {
  globalBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT,
                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
}

}  // namespace

// The draws' geometry stages that read what the compute passes wrote (lists, counters).
VkPipelineStageFlags GpuRenderer::drawShaderStages() const {
  return VK_PIPELINE_STAGE_VERTEX_SHADER_BIT |
         (vk_.tessellation()
              ? VK_PIPELINE_STAGE_TESSELLATION_CONTROL_SHADER_BIT | VK_PIPELINE_STAGE_TESSELLATION_EVALUATION_SHADER_BIT
              : 0u);
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

void GpuRenderer::pushPass(VkCommandBuffer cmd, uint32_t pass) {
  const shaderio::PassConstants constants{pass};
  vkCmdPushConstants(cmd, layout_, rendererStages(), 0, sizeof(constants), &constants);
}

void GpuRenderer::recordInstanceCull(VkCommandBuffer cmd, const FrameSettings& settings, uint32_t pass) {
  // 1. Reset the counters; the late pass carries on from the early one's (begin_late_pass.glsl).
  // 2. Instance culling, unless the persistent traversal's workers do it: then each instance counts as
  // pending until its culling has queued its items (traverse_persistent.comp).
  const bool inTraversal = cullsInTraversal(settings);
  if (pass == VGEO_PASS_LATE) {  // the late pass's counters, then the early pass's deferred items queued
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
    if (keepsPyramid(settings)) {  // else the pyramid's build began the late pass
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, beginLatePass_);
      vkCmdDispatch(cmd, 1, 1, 1);
      computeToCompute(cmd);
    }
    if (inTraversal) {  // else instance culling queues them (queue_deferred.glsl)
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, queueDeferred_);
      vkCmdDispatchIndirect(cmd, counters_.buffer, offsetof(shaderio::Counters, dispatch));
      computeToCompute(cmd);
    }
  } else {
    recordCounterReset(cmd, inTraversal ? uint32_t(scene_.data.instances.size()) : 0u);
  }
  if (inTraversal) return;
  const uint32_t instancesPerWorkgroup = cullInstancesPerWorkgroup(settings);
  const uint32_t tests = pass == VGEO_PASS_ONLY ? 0 : 1;  // the pipeline with the occlusion tests or without
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE,
                    instancesPerWorkgroup == VGEO_CULL_SERIAL_WORKGROUP ? cullSerial_[tests] : cull_[tests]);
  if (pass == VGEO_PASS_LATE)  // only the instances the early pass deferred, and its deferred items queued
    vkCmdDispatchIndirect(cmd, counters_.buffer, offsetof(shaderio::Counters, lateCullDispatch));
  else
    vkCmdDispatch(cmd, (uint32_t(scene_.data.instances.size()) + instancesPerWorkgroup - 1) / instancesPerWorkgroup, 1,
                  1);
  computeToCompute(cmd);
}

void GpuRenderer::recordTraversal(VkCommandBuffer cmd, const FrameSettings& settings, uint32_t pass) {
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
    const VkPipeline pipeline = settings.profileWorkers && persistentProfile_
                                    ? persistentProfile_
                                    : persistent_[pass == VGEO_PASS_ONLY ? 0 : 1];
    if (pass == VGEO_PASS_LATE) {  // no workers when the early pass deferred nothing (begin_late_pass.glsl)
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
      vkCmdDispatchIndirect(cmd, counters_.buffer, offsetof(shaderio::Counters, lateTraversalDispatch));
    } else {
      lastPass(pipeline, persistentWorkgroups_);
    }
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
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, cullSmallClusters_);  // the frame runs one of the two
  vkCmdDispatchIndirect(cmd, counters_.buffer, offsetof(shaderio::Counters, packedCullDispatch));
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

// 6. The compute rasterizers: the visibility buffer (or the overdraw counts) cleared, then the triangles
// binned to compute drawn into it, then the patches binned to compute; read by the resolve after the
// render pass.
void GpuRenderer::recordSoftwareRaster(VkCommandBuffer cmd, bool patches, bool clear) {
  if (clear) {  // the first pass of the frame; the late pass draws over the early one's
    vkCmdFillBuffer(cmd, visibility_.buffer, 0, VK_WHOLE_SIZE, 0);
    vkCmdFillBuffer(cmd, overdraw_.buffer, 0, VK_WHOLE_SIZE, 0);
    globalBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
  }
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, rasterSoftware_);
  vkCmdDispatchIndirect(cmd, counters_.buffer, offsetof(shaderio::Counters, rasterDispatch));
  if (patches) {  // the patches binned to compute, a workgroup each (atomics on the same words: ordered)
    computeToCompute(cmd);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, rasterPatches_);
    vkCmdDispatchIndirect(cmd, counters_.buffer, offsetof(shaderio::Counters, patchRasterDispatch));
  }
  // Read by the resolve, and with patches in compute by the draw of the hardware's patch grids.
  globalBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT |
                    (patches ? VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_VERTEX_SHADER_BIT : 0u),
                VK_ACCESS_SHADER_READ_BIT | (patches ? VkAccessFlags(VK_ACCESS_INDIRECT_COMMAND_READ_BIT) : 0u));
}

// 8. The resolve of the software rasterizer's pixels where they are nearer than the render pass's
// (resolve.comp), into the colour target.
void GpuRenderer::recordResolve(VkCommandBuffer cmd, uint32_t mode, bool patches, bool intoVisibility) {
  if (intoVisibility)  // the colour target, untouched by the render pass without attachments, into the resolve's layout
    layoutBarrier(cmd, color_, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                  VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                  VK_ACCESS_SHADER_WRITE_BIT);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, resolvePipeline(mode, patches, intoVisibility));
  vkCmdDispatch(cmd, (width_ + 7) / 8, (height_ + 7) / 8, 1);
}

// 7. The render pass: one indirect draw of the listed hardware triangles, one of the patches (not in the
// early pass). The late pass's keeps what the early one drew.
void GpuRenderer::recordRenderPass(VkCommandBuffer cmd, const FrameSettings& settings, bool intoVisibility,
                                   uint32_t pass) {
  if (intoVisibility) {  // the hardware's triangles into the visibility buffer, no attachments (draw_visibility.frag)
    VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    begin.renderPass = renderPassVisibility_;
    begin.framebuffer = framebufferVisibility_;
    begin.renderArea = {{0, 0}, {width_, height_}};
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &set_, 0, nullptr);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, drawVisibility_);
    vkCmdDrawIndirect(cmd, counters_.buffer, offsetof(shaderio::Counters, draw), 1, sizeof(VkDrawIndirectCommand));
    if (rastersPatchesInCompute(settings) && pass != VGEO_PASS_EARLY) {  // the hardware's patches, from their grids
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, drawGridVisibility_);
      vkCmdDrawIndirectCount(cmd, patchDraws_.buffer, 0, counters_.buffer,
                             offsetof(shaderio::Counters, hardwarePatches), patchCapacity_,
                             sizeof(VkDrawIndirectCommand));
    }
    vkCmdEndRenderPass(cmd);
    return;
  }
  VkClearValue clears[2];
  clears[0].color = {{settings.bgraTarget ? VGEO_BACKGROUND_B : VGEO_BACKGROUND_R, VGEO_BACKGROUND_G,
                      settings.bgraTarget ? VGEO_BACKGROUND_R : VGEO_BACKGROUND_B, 1.0f}};
  clears[1].depthStencil = {0.0f, 0};
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  // The resolve writes the background where nothing was drawn, except in the overdraw view (it adds).
  const bool resolved = softwareRaster(settings) != VGEO_RASTER_NONE && settings.mode != VGEO_MODE_OVERDRAW;
  begin.renderPass = pass == VGEO_PASS_LATE ? renderPassLoad_ : resolved ? renderPassResolved_ : renderPass_;
  begin.framebuffer = framebuffer_;
  begin.renderArea = {{0, 0}, {width_, height_}};
  begin.clearValueCount = 2;
  begin.pClearValues = clears;
  const bool patches = drawsPatches(settings) && pass != VGEO_PASS_EARLY;
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

// Between the passes of a frame with occlusion culling: the depth pyramid of what the early pass drew,
// in one dispatch whose last workgroup also begins the late pass (build_depth_pyramid.comp).
void GpuRenderer::recordDepthPyramid(VkCommandBuffer cmd) {
  // The early pass's depth: its compute rasterizers', its render pass's (the visibility buffer or the
  // depth target). The late pass's rasterizers then write them again (an execution dependency back).
  globalBarrier(cmd,
                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT |
                    VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, buildDepthPyramid_);
  vkCmdDispatch(cmd, (width_ + 31) / 32, (height_ + 31) / 32, 1);  // a workgroup a 32 x 32 pixel tile
  // Read by the late pass, or, after a one-pass frame, its counters (pyramidTilesDone) by the copies back.
  globalBarrier(
      cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT,
      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT |
          VK_ACCESS_TRANSFER_READ_BIT);
}

}  // namespace vgeo
