// gpu_pipelines.cpp: the GPU objects a frame records into, made once: the offscreen colour and depth
// targets with their render pass, the descriptor set layout, and every pipeline (the compute passes and
// the draw, plus the overdraw variant that adds every fragment). The frame itself is gpu_renderer.cpp.
#include "gpu_renderer.h"

#include "shaders/spirv.h"  // every shader of VGEO_SHADERS (CMakeLists.txt), both variants

// A shader's SPIR-V in the variant the scene needs: its arrays at their bindings, or by address (each
// shader is built both ways, CMakeLists.txt).
#define VGEO_SPIRV(name) \
  (sceneByAddress_ ? name##_by_address : name), (sceneByAddress_ ? sizeof(name##_by_address) : sizeof(name))

namespace vgeo {

// The offscreen colour and depth targets and the render pass that draws into them.
void GpuRenderer::createTargets() {
  VkDevice dev = vk_.device();
  createImage(vk_, width_, height_, VK_FORMAT_R8G8B8A8_UNORM,
              VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_STORAGE_BIT,
              VK_IMAGE_ASPECT_COLOR_BIT, color_, colorMemory_, colorView_);
  createImage(vk_, width_, height_, VK_FORMAT_D32_SFLOAT,
              VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, VK_IMAGE_ASPECT_DEPTH_BIT,
              depth_, depthMemory_, depthView_);

  VkAttachmentDescription attachments[2] = {};
  attachments[0].format = VK_FORMAT_R8G8B8A8_UNORM;
  attachments[0].samples = VK_SAMPLE_COUNT_1_BIT;
  attachments[0].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  attachments[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  attachments[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  attachments[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  attachments[0].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  // After the pass the resolve (resolve.comp) writes the colour as a storage image and reads the depth,
  // then the colour is copied out.
  attachments[0].finalLayout = VK_IMAGE_LAYOUT_GENERAL;
  attachments[1] = attachments[0];
  attachments[1].format = VK_FORMAT_D32_SFLOAT;
  attachments[1].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
  VkAttachmentReference colorRef{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
      depthRef{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &colorRef;
  subpass.pDepthStencilAttachment = &depthRef;
  // Earlier frames' copy of the colour image and depth use finish before this pass writes them again
  // (their resolve too, by the barrier that opens every frame); with occlusion culling, the early pass's
  // draws and the depth pyramid's reads of its depth (compute) before the late pass's (the three render
  // passes must be alike but for their load operations and layouts, dependencies included). Not this
  // frame's compute rasterizers: they may run beside the draws; the resolve waits for both.
  VkSubpassDependency deps[2] = {};
  deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  deps[0].dstSubpass = 0;
  deps[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT |
                         VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
  deps[0].srcAccessMask =
      VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT;
  deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                          VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
  deps[1].srcSubpass = 0;
  deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  deps[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
  deps[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
  VkRenderPassCreateInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  rp.attachmentCount = 2;
  rp.pAttachments = attachments;
  rp.subpassCount = 1;
  rp.pSubpasses = &subpass;
  rp.dependencyCount = 2;
  rp.pDependencies = deps;
  vkCheck(vkCreateRenderPass(dev, &rp, nullptr, &renderPass_), "vkCreateRenderPass");
  // The same pass leaving the colour as it finds it, for frames whose resolve writes every pixel the
  // draws leave (the clear of a 1920x1080 target is not free on every GPU).
  attachments[0].loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  vkCheck(vkCreateRenderPass(dev, &rp, nullptr, &renderPassResolved_), "vkCreateRenderPass");
  // The late pass of a frame with occlusion culling draws over the early pass's colour and depth, after
  // the early pass's draws and the depth pyramid's reads of the depth (compute).
  attachments[0].loadOp = attachments[1].loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  attachments[0].initialLayout = VK_IMAGE_LAYOUT_GENERAL;
  attachments[1].initialLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL;
  vkCheck(vkCreateRenderPass(dev, &rp, nullptr, &renderPassLoad_), "vkCreateRenderPass (late pass)");
  VkImageView views[2] = {colorView_, depthView_};
  VkFramebufferCreateInfo fb{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  fb.renderPass = renderPass_;
  fb.attachmentCount = 2;
  fb.pAttachments = views;
  fb.width = width_;
  fb.height = height_;
  fb.layers = 1;
  vkCheck(vkCreateFramebuffer(dev, &fb, nullptr, &framebuffer_), "vkCreateFramebuffer");
  // The render pass of frames whose hardware triangles go into the visibility buffer too
  // (draw_visibility.frag): no attachments, so nothing to clear or store. Its fragments' atomics come
  // after the compute rasterizers' (and its vertices read the patch grids they wrote), and before the
  // resolve's reads.
  VkSubpassDescription noAttachments{};
  noAttachments.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  VkSubpassDependency bareDeps[2] = {};
  bareDeps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  bareDeps[0].srcStageMask = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
  bareDeps[0].srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  bareDeps[0].dstStageMask = VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
  bareDeps[0].dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
  bareDeps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  bareDeps[1].srcStageMask = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
  bareDeps[1].srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  bareDeps[1].dstStageMask = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
  bareDeps[1].dstAccessMask = VK_ACCESS_SHADER_READ_BIT;
  rp.attachmentCount = 0;
  rp.pSubpasses = &noAttachments;
  rp.pDependencies = bareDeps;
  vkCheck(vkCreateRenderPass(dev, &rp, nullptr, &renderPassVisibility_), "vkCreateRenderPass (visibility)");
  fb.renderPass = renderPassVisibility_;
  fb.attachmentCount = 0;
  vkCheck(vkCreateFramebuffer(dev, &fb, nullptr, &framebufferVisibility_), "vkCreateFramebuffer (visibility)");
  // The resolve's descriptor names the depth image in its read-only layout even in frames that skip the
  // depth pass: it starts there.
  VkCommandBuffer cmd = vk_.beginCommands();
  layoutBarrier(cmd, depth_, VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
  vk_.submitAndWait(cmd);
  VkSamplerCreateInfo sampler{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};  // texelFetch only
  vkCheck(vkCreateSampler(dev, &sampler, nullptr, &depthSampler_), "vkCreateSampler");
}

void GpuRenderer::createPipelines(bool softwareRaster) {
  createDescriptorSet();
  createComputePipelines(softwareRaster);
  createDrawPipelines();
}

// The one descriptor set of shaderio_frame.h's bindings, seen by every stage, and the pipeline layout.
void GpuRenderer::createDescriptorSet() {
  VkDevice dev = vk_.device();
  VkDescriptorSetLayoutBinding bindings[kRendererBindings];
  for (uint32_t i = 0; i < kRendererBindings; i++) {
    bindings[i] = {i, descriptorType(i), 1, rendererStages(), nullptr};
  }
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.bindingCount = kRendererBindings;
  setInfo.pBindings = bindings;
  vkCheck(vkCreateDescriptorSetLayout(dev, &setInfo, nullptr, &setLayout_), "vkCreateDescriptorSetLayout");
  VkDescriptorPoolSize sizes[4] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                   {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1},
                                   {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1},
                                   {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kRendererBindings - 3}};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = 1;
  poolInfo.poolSizeCount = 4;
  poolInfo.pPoolSizes = sizes;
  vkCheck(vkCreateDescriptorPool(dev, &poolInfo, nullptr, &descriptorPool_), "vkCreateDescriptorPool");
  VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  alloc.descriptorPool = descriptorPool_;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &setLayout_;
  vkCheck(vkAllocateDescriptorSets(dev, &alloc, &set_), "vkAllocateDescriptorSets");
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &setLayout_;
  const VkPushConstantRange passConstants{rendererStages(), 0, sizeof(shaderio::PassConstants)};
  layoutInfo.pushConstantRangeCount = 1;
  layoutInfo.pPushConstantRanges = &passConstants;
  vkCheck(vkCreatePipelineLayout(dev, &layoutInfo, nullptr, &layout_), "vkCreatePipelineLayout");
}

Pipeline GpuRenderer::computePipeline(const uint32_t* code, size_t bytes, const VkSpecializationInfo* specialization) {
  VkDevice dev = vk_.device();
  VkShaderModule module = vk_.createShaderModule(code, bytes);
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                nullptr,
                0,
                VK_SHADER_STAGE_COMPUTE_BIT,
                module,
                "main",
                specialization};
  info.layout = layout_;
  VkPipeline pipeline;
  vkCheck(vkCreateComputePipelines(dev, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline), "vkCreateComputePipelines");
  vkDestroyShaderModule(dev, module, nullptr);
  return Pipeline(dev, pipeline);
}

VkPipeline GpuRenderer::resolvePipeline(uint32_t mode, bool patches, bool everyPixel) {
  Pipeline& pipeline = resolve_[mode][patches ? 1 : 0][everyPixel ? 1 : 0];
  if (!pipeline) {
    const uint32_t constants[3] = {mode, patches ? 1u : 0u, everyPixel ? 1u : 0u};  // VkBool32
    const VkSpecializationMapEntry entries[3] = {
        {VGEO_SPEC_VIEW_MODE, 0, sizeof(uint32_t)},
        {VGEO_SPEC_RESOLVE_PATCHES, sizeof(uint32_t), sizeof(uint32_t)},
        {VGEO_SPEC_RESOLVE_EVERY_PIXEL, 2 * sizeof(uint32_t), sizeof(uint32_t)}};
    const VkSpecializationInfo view{3, entries, sizeof(constants), constants};
    pipeline = computePipeline(VGEO_SPIRV(resolve_comp), &view);
  }
  return pipeline;
}

void GpuRenderer::createComputePipelines(bool softwareRaster) {
  // Instance culling and the traversals with the occlusion tests, and without them for one-pass frames
  // (VGEO_SPEC_OCCLUSION; the levels and flat traversals only run those). Tests a lane between draw-list
  // atomics (traverse_persistent.comp, runRound): 1 on lavapipe.
  const uint32_t laneTests = vk_.isLavapipe() ? 1u : 4u;
  const uint32_t constants[2][2] = {{laneTests, 0u}, {laneTests, 1u}};  // (lane tests, occlusion as VkBool32)
  const VkSpecializationMapEntry entries[2] = {{VGEO_SPEC_OCCLUSION, sizeof(uint32_t), sizeof(uint32_t)},
                                               {VGEO_SPEC_LANE_TESTS, 0, sizeof(uint32_t)}};
  VkSpecializationInfo specializations[2];
  for (uint32_t occlusion = 0; occlusion < 2; occlusion++) {
    specializations[occlusion] = {2, entries, sizeof(constants[occlusion]), constants[occlusion]};
    cull_[occlusion] = computePipeline(VGEO_SPIRV(cull_instances_comp), &specializations[occlusion]);
    cullSerial_[occlusion] = computePipeline(VGEO_SPIRV(cull_instances_comp_cull_serial), &specializations[occlusion]);
    persistent_[occlusion] = computePipeline(VGEO_SPIRV(traverse_persistent_comp), &specializations[occlusion]);
  }
  if (vk_.deviceClock())
    persistentProfile_ = computePipeline(VGEO_SPIRV(traverse_persistent_comp_profile), &specializations[1]);
  level_ = computePipeline(VGEO_SPIRV(traverse_level_comp), &specializations[0]);
  prepareLevel_ = computePipeline(VGEO_SPIRV(prepare_level_comp));
  flat_ = computePipeline(VGEO_SPIRV(traverse_flat_comp), &specializations[0]);
  prepareFlat_ = computePipeline(VGEO_SPIRV(prepare_flat_comp));
  resetFlat_ = computePipeline(VGEO_SPIRV(reset_flat_comp));
  finalize_ = computePipeline(VGEO_SPIRV(finalize_comp));
  cullTriangles_ = computePipeline(VGEO_SPIRV(cull_triangles_comp));
  cullSmallClusters_ = computePipeline(VGEO_SPIRV(cull_small_clusters_comp));
  preparePatches_ = computePipeline(VGEO_SPIRV(prepare_patches_comp));
  cullPatches_ = computePipeline(VGEO_SPIRV(cull_patches_comp));
  finalizeTriangles_ = computePipeline(VGEO_SPIRV(finalize_triangles_comp));
  buildDepthPyramid_ = computePipeline(VGEO_SPIRV(build_depth_pyramid_comp));
  beginLatePass_ = computePipeline(VGEO_SPIRV(begin_late_pass_comp));
  queueDeferred_ = computePipeline(VGEO_SPIRV(queue_deferred_comp));
  if (softwareRaster) {
    rasterSoftware_ = computePipeline(VGEO_SPIRV(raster_software_comp));
    rasterPatches_ = computePipeline(VGEO_SPIRV(raster_patches_comp));
  }
}

// The draw of listed triangles, its overdraw variant (every fragment adds, nothing hidden), and the same
// two for patches where the device has tessellation shaders.
void GpuRenderer::createDrawPipelines() {
  VkDevice dev = vk_.device();
  VkShaderModule vert = vk_.createShaderModule(VGEO_SPIRV(draw_vert));
  VkShaderModule frag = vk_.createShaderModule(VGEO_SPIRV(draw_frag));
  VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0,
                                                VK_SHADER_STAGE_VERTEX_BIT, vert, "main", nullptr},
                                               {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0,
                                                VK_SHADER_STAGE_FRAGMENT_BIT, frag, "main", nullptr}};
  VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkViewport viewport{0, 0, float(width_), float(height_), 0, 1};
  VkRect2D scissor{{0, 0}, {width_, height_}};
  VkPipelineViewportStateCreateInfo viewportState{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewportState.viewportCount = 1;
  viewportState.pViewports = &viewport;
  viewportState.scissorCount = 1;
  viewportState.pScissors = &scissor;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;  // open meshes are seen from both sides
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depth.depthTestEnable = VK_TRUE;
  depth.depthWriteEnable = VK_TRUE;
  depth.depthCompareOp = VK_COMPARE_OP_GREATER;  // reversed depth (camera.cpp)
  VkPipelineColorBlendAttachmentState blend{};
  blend.colorWriteMask = 0xf;
  VkPipelineColorBlendStateCreateInfo blendState{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blendState.attachmentCount = 1;
  blendState.pAttachments = &blend;
  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.stageCount = 2;
  info.pStages = stages;
  info.pVertexInputState = &vertexInput;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewportState;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blendState;
  info.layout = layout_;
  info.renderPass = renderPass_;
  blend.srcColorBlendFactor = blend.dstColorBlendFactor = VK_BLEND_FACTOR_ONE;
  blend.srcAlphaBlendFactor = blend.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
  blend.colorBlendOp = blend.alphaBlendOp = VK_BLEND_OP_ADD;
  // Each draw in two pipelines: the views that hide what lies behind (depth test and write), and the
  // overdraw view (every fragment adds, nothing is hidden).
  auto graphicsPipeline = [&](const char* what) {
    VkPipeline pipeline;
    vkCheck(vkCreateGraphicsPipelines(dev, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline), what);
    return Pipeline(dev, pipeline);
  };
  auto createViews = [&](const VkPipelineShaderStageCreateInfo* shaderStages, uint32_t count, Pipeline& hidden,
                         Pipeline& overdraw, const char* what) {
    info.stageCount = count;
    info.pStages = shaderStages;
    depth.depthTestEnable = depth.depthWriteEnable = VK_TRUE;
    blend.blendEnable = VK_FALSE;
    hidden = graphicsPipeline(what);
    depth.depthTestEnable = depth.depthWriteEnable = VK_FALSE;
    blend.blendEnable = VK_TRUE;
    overdraw = graphicsPipeline(what);
  };
  createViews(stages, 2, draw_, drawOverdraw_, "vkCreateGraphicsPipelines");
  // The same draw into the visibility buffer (draw_visibility.frag): no attachments, no depth test, no
  // blending; every view (the fragment shader counts in the overdraw view).
  if (rasterSoftware_) {
    VkShaderModule visibilityVert = vk_.createShaderModule(VGEO_SPIRV(draw_vert_visibility_only));
    VkShaderModule visibilityFrag = vk_.createShaderModule(VGEO_SPIRV(draw_visibility_frag));
    VkPipelineShaderStageCreateInfo visibilityStages[2] = {
        {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT, visibilityVert,
         "main", nullptr},
        {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT, visibilityFrag,
         "main", nullptr}};
    info.stageCount = 2;
    info.pStages = visibilityStages;
    info.renderPass = renderPassVisibility_;
    depth.depthTestEnable = depth.depthWriteEnable = VK_FALSE;
    blendState.attachmentCount = 0;
    drawVisibility_ = graphicsPipeline("vkCreateGraphicsPipelines (visibility)");
    // The hardware's patches from their grids (patch_grid.vert), into the same buffer.
    VkShaderModule gridVert = vk_.createShaderModule(VGEO_SPIRV(patch_grid_vert));
    visibilityStages[0].module = gridVert;
    drawGridVisibility_ = graphicsPipeline("vkCreateGraphicsPipelines (patch grids)");
    vkDestroyShaderModule(dev, gridVert, nullptr);
    blendState.attachmentCount = 1;
    info.renderPass = renderPass_;
    vkDestroyShaderModule(dev, visibilityVert, nullptr);
    vkDestroyShaderModule(dev, visibilityFrag, nullptr);
  }
  // The patch draw: the same state, one control point a patch, tessellated (patch.tesc, patch.tese).
  // Without tessellation shaders on the device, leaves stay triangles.
  if (vk_.tessellation()) {
    VkShaderModule patchVert = vk_.createShaderModule(VGEO_SPIRV(patch_vert));
    VkShaderModule tesc = vk_.createShaderModule(VGEO_SPIRV(patch_tesc));
    VkShaderModule tese = vk_.createShaderModule(VGEO_SPIRV(patch_tese));
    VkPipelineShaderStageCreateInfo patchStages[4] = {
        {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT, patchVert, "main",
         nullptr},
        {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT,
         tesc, "main", nullptr},
        {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT,
         tese, "main", nullptr},
        {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT, frag, "main",
         nullptr}};
    VkPipelineTessellationStateCreateInfo tessellation{VK_STRUCTURE_TYPE_PIPELINE_TESSELLATION_STATE_CREATE_INFO};
    tessellation.patchControlPoints = 1;
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_PATCH_LIST;
    info.pTessellationState = &tessellation;
    createViews(patchStages, 4, drawPatches_, drawPatchesOverdraw_, "vkCreateGraphicsPipelines (patches)");
    for (VkShaderModule m : {patchVert, tesc, tese}) vkDestroyShaderModule(dev, m, nullptr);
  }
  vkDestroyShaderModule(dev, vert, nullptr);
  vkDestroyShaderModule(dev, frag, nullptr);
}

}  // namespace vgeo
