// gpu_renderer.cpp: the frame. Read renderFrame() top to bottom: it is the list of passes.
//   1. reset counters            (transfer)
//   2. cull_instances.comp       one thread an instance -> queue of (instance, BVH root)
//   3. traversal                 persistent: one dispatch of resident workgroups draining the queue
//                                levels: per depth, prepare_level.comp then traverse_level.comp (indirect)
//                                flat: prepare_flat.comp then traverse_flat.comp (one thread a cluster)
//   4. finalize.comp             indirect draw arguments from the draw-list count
//   5. render pass: one vkCmdDrawIndirect of 384 vertices x listed clusters (draw.vert, draw.frag)
//   6. copies back: counters (and the image / draw list when asked), read once the frame is done
// No host read-back happens inside the frame; the host reads the counters after it, and a frame that
// overflowed grows the buffers for the next one.
#include "gpu_renderer.h"

#include <chrono>
#include <cstring>
#include <stdexcept>

#include "shaders/cull_instances_comp.h"
#include "shaders/draw_frag.h"
#include "shaders/draw_vert.h"
#include "shaders/finalize_comp.h"
#include "shaders/prepare_flat_comp.h"
#include "shaders/prepare_level_comp.h"
#include "shaders/reset_flat_comp.h"
#include "shaders/traverse_flat_comp.h"
#include "shaders/traverse_level_comp.h"
#include "shaders/traverse_persistent_comp.h"

namespace vgeo {
namespace {

constexpr uint32_t kSceneBindings = 10;  // bindings 1..9: geometries .. BVH nodes; 13: cluster cones
constexpr uint32_t kBindings = 14;
// lavapipe ends every loop after 65,535 iterations per invocation (GPU-NOTES 1): persistent workers
// leave on their own well before, holding nothing, and enough of them are dispatched to carry on.
constexpr uint32_t kLavapipeIterationBudget = 50000;
constexpr uint32_t kLavapipeWorkgroups = 128;

void globalBarrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkAccessFlags srcAccess, VkPipelineStageFlags dst, VkAccessFlags dstAccess) {
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

const char* traversalName(Traversal t) {
  return t == Traversal::Persistent ? "persistent" : t == Traversal::Levels ? "levels" : "flat";
}

GpuRenderer::GpuRenderer(VulkanContext& context, const RenderScene& scene, uint32_t width, uint32_t height)
    : vk_(context), scene_(scene), width_(width), height_(height) {
  const VgeoData& d = scene.data;
  VkDeviceSize range = vk_.properties().limits.maxStorageBufferRange;
  struct Section {
    const void* data;
    size_t bytes;
  } sections[kSceneBindings] = {
      {d.geometries.data(), d.geometries.size() * sizeof(shaderio::Geometry)},
      {d.instances.data(), d.instances.size() * sizeof(shaderio::Instance)},
      {d.positions.data(), d.positions.size() * sizeof(float)},
      {d.normals.data(), d.normals.size() * sizeof(uint32_t)},
      {d.clusters.data(), d.clusters.size() * sizeof(shaderio::Cluster)},
      {d.clusterVertices.data(), d.clusterVertices.size() * sizeof(uint32_t)},
      {d.clusterTriangles.data(), d.clusterTriangles.size() * sizeof(uint32_t)},
      {d.groups.data(), d.groups.size() * sizeof(shaderio::Group)},
      {d.nodes.data(), d.nodes.size() * sizeof(shaderio::BvhNode)},
      {d.clusterCones.data(), d.clusterCones.size() * sizeof(shaderio::ClusterCone)},
  };
  for (const auto& s : sections) {
    if (s.bytes > range)
      throw std::runtime_error("scene too large for this device: a buffer of " + std::to_string(s.bytes >> 20) +
                               " MiB exceeds maxStorageBufferRange (" + std::to_string(range >> 20) + " MiB)");
    sceneBuffers_.push_back(vk_.createBuffer(s.bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT));
    vk_.upload(sceneBuffers_.back(), s.data, s.bytes);
  }
  frameData_ = vk_.createBuffer(sizeof(shaderio::FrameData), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
  counters_ = vk_.createBuffer(sizeof(shaderio::Counters), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
  countersReadback_ = vk_.createBuffer(sizeof(shaderio::Counters), VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
  imageReadback_ = vk_.createBuffer(VkDeviceSize(width_) * height_ * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);

  if (vk_.isLavapipe()) {
    claimMode_ = 1;
    iterationBudget_ = kLavapipeIterationBudget;
    persistentWorkgroups_ = kLavapipeWorkgroups;
  } else {
    // Four workgroups an SM where NVIDIA tells the SM count. Measured on an H100 (132 SMs), armadillo
    // --subdiv 2 at 1920x1080: 10k instances 0.24 ms with 4,224 workgroups (all the device holds),
    // 0.09 ms with 528, 0.08 with 264; 100k instances 0.29 / 0.11 / 0.15 ms. Claiming past the frontier
    // makes every extra workgroup a poller of empty slots; four an SM keeps the SMs busy without that.
    persistentWorkgroups_ = 512;
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(vk_.physicalDevice(), nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateDeviceExtensionProperties(vk_.physicalDevice(), nullptr, &count, extensions.data());
    for (const auto& e : extensions)
      if (std::strcmp(e.extensionName, VK_NV_SHADER_SM_BUILTINS_EXTENSION_NAME) == 0) {
        VkPhysicalDeviceShaderSMBuiltinsPropertiesNV sm{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_SM_BUILTINS_PROPERTIES_NV};
        VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
        props.pNext = &sm;
        vkGetPhysicalDeviceProperties2(vk_.physicalDevice(), &props);
        persistentWorkgroups_ = std::max(1u, sm.shaderSMCount * 4u);
      }
  }
  createTargets();
  createQueueAndDrawList();
  createPipelines();
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
  q.queryCount = 3;
  vkCheck(vkCreateQueryPool(vk_.device(), &q, nullptr, &queries_), "vkCreateQueryPool");
}

GpuRenderer::~GpuRenderer() {
  VkDevice dev = vk_.device();
  vkDeviceWaitIdle(dev);
  for (VkPipeline p : {cull_, persistent_, level_, prepareLevel_, flat_, prepareFlat_, resetFlat_, finalize_, draw_, drawOverdraw_}) vkDestroyPipeline(dev, p, nullptr);
  vkDestroyPipelineLayout(dev, layout_, nullptr);
  vkDestroyDescriptorPool(dev, descriptorPool_, nullptr);
  vkDestroyDescriptorSetLayout(dev, setLayout_, nullptr);
  vkDestroyQueryPool(dev, queries_, nullptr);
  vkDestroyFramebuffer(dev, framebuffer_, nullptr);
  vkDestroyRenderPass(dev, renderPass_, nullptr);
  vkDestroyImageView(dev, colorView_, nullptr);
  vkDestroyImageView(dev, depthView_, nullptr);
  vkDestroyImage(dev, color_, nullptr);
  vkDestroyImage(dev, depth_, nullptr);
  vkFreeMemory(dev, colorMemory_, nullptr);
  vkFreeMemory(dev, depthMemory_, nullptr);
  for (Buffer* b : {&frameData_, &counters_, &countersReadback_, &queue_, &drawList_, &drawListReadback_, &imageReadback_}) vk_.destroyBuffer(*b);
  for (Buffer& b : sceneBuffers_) vk_.destroyBuffer(b);
}

void GpuRenderer::createTargets() {
  VkDevice dev = vk_.device();
  auto makeImage = [&](VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect, VkImage& image, VkDeviceMemory& memory, VkImageView& view) {
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {width_, height_, 1};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    vkCheck(vkCreateImage(dev, &info, nullptr, &image), "vkCreateImage");
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(dev, image, &req);
    VkPhysicalDeviceMemoryProperties mem;
    vkGetPhysicalDeviceMemoryProperties(vk_.physicalDevice(), &mem);
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    for (uint32_t i = 0; i < mem.memoryTypeCount; i++)
      if ((req.memoryTypeBits & (1u << i)) && (mem.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)) {
        alloc.memoryTypeIndex = i;
        break;
      }
    vkCheck(vkAllocateMemory(dev, &alloc, nullptr, &memory), "vkAllocateMemory (image)");
    vkCheck(vkBindImageMemory(dev, image, memory, 0), "vkBindImageMemory");
    VkImageViewCreateInfo v{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    v.image = image;
    v.viewType = VK_IMAGE_VIEW_TYPE_2D;
    v.format = format;
    v.subresourceRange = {aspect, 0, 1, 0, 1};
    vkCheck(vkCreateImageView(dev, &v, nullptr, &view), "vkCreateImageView");
  };
  makeImage(VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT, color_, colorMemory_, colorView_);
  makeImage(VK_FORMAT_D32_SFLOAT, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT, depth_, depthMemory_, depthView_);

  VkAttachmentDescription attachments[2] = {};
  attachments[0].format = VK_FORMAT_R8G8B8A8_UNORM;
  attachments[0].samples = VK_SAMPLE_COUNT_1_BIT;
  attachments[0].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  attachments[0].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  attachments[0].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  attachments[0].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  attachments[0].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  attachments[0].finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  attachments[1] = attachments[0];
  attachments[1].format = VK_FORMAT_D32_SFLOAT;
  attachments[1].storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  attachments[1].finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
  VkAttachmentReference colorRef{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL}, depthRef{1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &colorRef;
  subpass.pDepthStencilAttachment = &depthRef;
  // Earlier frames' copy of the colour image and depth use finish before this pass writes them again.
  VkSubpassDependency deps[2] = {};
  deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  deps[0].dstSubpass = 0;
  deps[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  deps[0].srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT;
  deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                          VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
  deps[1].srcSubpass = 0;
  deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  deps[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  deps[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  VkRenderPassCreateInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  rp.attachmentCount = 2;
  rp.pAttachments = attachments;
  rp.subpassCount = 1;
  rp.pSubpasses = &subpass;
  rp.dependencyCount = 2;
  rp.pDependencies = deps;
  vkCheck(vkCreateRenderPass(dev, &rp, nullptr, &renderPass_), "vkCreateRenderPass");
  VkImageView views[2] = {colorView_, depthView_};
  VkFramebufferCreateInfo fb{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  fb.renderPass = renderPass_;
  fb.attachmentCount = 2;
  fb.pAttachments = views;
  fb.width = width_;
  fb.height = height_;
  fb.layers = 1;
  vkCheck(vkCreateFramebuffer(dev, &fb, nullptr, &framebuffer_), "vkCreateFramebuffer");
}

void GpuRenderer::createQueueAndDrawList() {
  VkDeviceSize range = vk_.properties().limits.maxStorageBufferRange;
  queueCapacity_ = uint32_t(std::min<VkDeviceSize>(queueCapacity_, range / 8));
  drawCapacity_ = uint32_t(std::min<VkDeviceSize>(drawCapacity_, range / 8));
  queue_ = vk_.createBuffer(VkDeviceSize(queueCapacity_) * 8, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  drawList_ = vk_.createBuffer(VkDeviceSize(drawCapacity_) * 8, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  // Every queue slot starts unwritten; consumers put them back that way.
  VkCommandBuffer cmd = vk_.beginCommands();
  vkCmdFillBuffer(cmd, queue_.buffer, 0, VK_WHOLE_SIZE, VGEO_INVALID);
  vk_.submitAndWait(cmd);
}

void GpuRenderer::setCapacities(uint32_t queueItems, uint32_t drawEntries) {
  vkDeviceWaitIdle(vk_.device());
  vk_.destroyBuffer(queue_);
  vk_.destroyBuffer(drawList_);
  queueCapacity_ = std::max(queueItems, 1u);
  drawCapacity_ = std::max(drawEntries, 1u);
  createQueueAndDrawList();
  writeDescriptors();
}

void GpuRenderer::createPipelines() {
  VkDevice dev = vk_.device();
  VkDescriptorSetLayoutBinding bindings[kBindings];
  for (uint32_t i = 0; i < kBindings; i++) {
    bindings[i] = {i, i == 0 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
                   VK_SHADER_STAGE_COMPUTE_BIT | VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
  }
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.bindingCount = kBindings;
  setInfo.pBindings = bindings;
  vkCheck(vkCreateDescriptorSetLayout(dev, &setInfo, nullptr, &setLayout_), "vkCreateDescriptorSetLayout");
  VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1}, {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kBindings - 1}};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = 1;
  poolInfo.poolSizeCount = 2;
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
  vkCheck(vkCreatePipelineLayout(dev, &layoutInfo, nullptr, &layout_), "vkCreatePipelineLayout");

  auto compute = [&](const uint32_t* code, size_t bytes) {
    VkShaderModule module = vk_.createShaderModule(code, bytes);
    VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_COMPUTE_BIT, module, "main", nullptr};
    info.layout = layout_;
    VkPipeline pipeline;
    vkCheck(vkCreateComputePipelines(dev, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline), "vkCreateComputePipelines");
    vkDestroyShaderModule(dev, module, nullptr);
    return pipeline;
  };
  cull_ = compute(cull_instances_comp, sizeof(cull_instances_comp));
  persistent_ = compute(traverse_persistent_comp, sizeof(traverse_persistent_comp));
  level_ = compute(traverse_level_comp, sizeof(traverse_level_comp));
  prepareLevel_ = compute(prepare_level_comp, sizeof(prepare_level_comp));
  flat_ = compute(traverse_flat_comp, sizeof(traverse_flat_comp));
  prepareFlat_ = compute(prepare_flat_comp, sizeof(prepare_flat_comp));
  resetFlat_ = compute(reset_flat_comp, sizeof(reset_flat_comp));
  finalize_ = compute(finalize_comp, sizeof(finalize_comp));

  VkShaderModule vert = vk_.createShaderModule(draw_vert, sizeof(draw_vert));
  VkShaderModule frag = vk_.createShaderModule(draw_frag, sizeof(draw_frag));
  VkPipelineShaderStageCreateInfo stages[2] = {
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT, vert, "main", nullptr},
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT, frag, "main", nullptr}};
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
  vkCheck(vkCreateGraphicsPipelines(dev, VK_NULL_HANDLE, 1, &info, nullptr, &draw_), "vkCreateGraphicsPipelines");
  // Overdraw: every fragment adds, nothing is hidden.
  depth.depthTestEnable = VK_FALSE;
  depth.depthWriteEnable = VK_FALSE;
  blend.blendEnable = VK_TRUE;
  blend.srcColorBlendFactor = blend.dstColorBlendFactor = VK_BLEND_FACTOR_ONE;
  blend.srcAlphaBlendFactor = blend.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
  blend.colorBlendOp = blend.alphaBlendOp = VK_BLEND_OP_ADD;
  vkCheck(vkCreateGraphicsPipelines(dev, VK_NULL_HANDLE, 1, &info, nullptr, &drawOverdraw_), "vkCreateGraphicsPipelines");
  vkDestroyShaderModule(dev, vert, nullptr);
  vkDestroyShaderModule(dev, frag, nullptr);
}

void GpuRenderer::writeDescriptors() {
  std::vector<const Buffer*> buffers{&frameData_};
  for (uint32_t i = 0; i < 9; i++) buffers.push_back(&sceneBuffers_[i]);
  buffers.push_back(&counters_);
  buffers.push_back(&queue_);
  buffers.push_back(&drawList_);
  buffers.push_back(&sceneBuffers_[9]);
  VkDescriptorBufferInfo infos[kBindings];
  VkWriteDescriptorSet writes[kBindings];
  for (uint32_t i = 0; i < kBindings; i++) {
    infos[i] = {buffers[i]->buffer, 0, VK_WHOLE_SIZE};
    writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET, nullptr, set_, i, 0, 1,
                 i == 0 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, nullptr, &infos[i], nullptr};
  }
  vkUpdateDescriptorSets(vk_.device(), kBindings, writes, 0, nullptr);
}

// Zeroes the counters (earlier submissions are ordered before it by the opening barrier) and binds the
// descriptor set for the compute passes.
void GpuRenderer::recordCounterReset(VkCommandBuffer cmd) {
  globalBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT,
                VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
  shaderio::Counters zero{};
  vkCmdUpdateBuffer(cmd, counters_.buffer, 0, sizeof(zero), &zero);
  globalBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
}

void GpuRenderer::recordTraversal(VkCommandBuffer cmd, const FrameSettings& settings) {
  // 1. Reset the counters.
  recordCounterReset(cmd);
  // 2. Instance culling.
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, cull_);
  vkCmdDispatch(cmd, (uint32_t(scene_.data.instances.size()) + 63) / 64, 1, 1);
  computeToCompute(cmd);
  // 3. Traversal.
  if (settings.traversal == Traversal::Persistent) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, persistent_);
    vkCmdDispatch(cmd, persistentWorkgroups_, 1, 1);
    computeToCompute(cmd);
  } else if (settings.traversal == Traversal::Levels) {
    // Root nodes, then one level of nodes per dispatch, then the groups: depth + 1 windows.
    for (uint32_t level = 0; level <= scene_.maxBvhDepth; level++) {
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, prepareLevel_);
      vkCmdDispatch(cmd, 1, 1, 1);
      computeToCompute(cmd);
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, level_);
      vkCmdDispatchIndirect(cmd, counters_.buffer, offsetof(shaderio::Counters, dispatch));
      computeToCompute(cmd);
    }
  } else {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, prepareFlat_);
    vkCmdDispatch(cmd, 1, 1, 1);
    computeToCompute(cmd);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, flat_);
    vkCmdDispatchIndirect(cmd, counters_.buffer, offsetof(shaderio::Counters, dispatch));
    computeToCompute(cmd);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, resetFlat_);
    vkCmdDispatch(cmd, (uint32_t(scene_.data.instances.size()) + 63) / 64, 1, 1);
    computeToCompute(cmd);
  }
  // 4. Draw arguments.
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, finalize_);
  vkCmdDispatch(cmd, 1, 1, 1);
  globalBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT |
                    VK_PIPELINE_STAGE_TRANSFER_BIT,
                VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT);
}

void GpuRenderer::recordDraw(VkCommandBuffer cmd, const FrameSettings& settings) {
  // 5. One indirect draw.
  if (settings.draw) recordRenderPass(cmd, settings);
  // 6. Copies back.
  VkBufferCopy all{0, 0, sizeof(shaderio::Counters)};
  vkCmdCopyBuffer(cmd, counters_.buffer, countersReadback_.buffer, 1, &all);
  if (settings.readImage && settings.draw) {
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {width_, height_, 1};
    vkCmdCopyImageToBuffer(cmd, color_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, imageReadback_.buffer, 1, &region);
  }
  if (settings.readDrawList) {
    VkBufferCopy list{0, 0, drawList_.size};
    vkCmdCopyBuffer(cmd, drawList_.buffer, drawListReadback_.buffer, 1, &list);
  }
  globalBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
}

void GpuRenderer::recordRenderPass(VkCommandBuffer cmd, const FrameSettings& settings) {
  VkClearValue clears[2];
  clears[0].color = {{0.02f, 0.025f, 0.035f, 1.0f}};
  clears[1].depthStencil = {0.0f, 0};
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  begin.renderPass = renderPass_;
  begin.framebuffer = framebuffer_;
  begin.renderArea = {{0, 0}, {width_, height_}};
  begin.clearValueCount = 2;
  begin.pClearValues = clears;
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, settings.mode == VGEO_MODE_OVERDRAW ? drawOverdraw_ : draw_);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &set_, 0, nullptr);
  vkCmdDrawIndirect(cmd, counters_.buffer, offsetof(shaderio::Counters, draw), 1, sizeof(VkDrawIndirectCommand));
  vkCmdEndRenderPass(cmd);
}

FrameResult GpuRenderer::renderFrame(const FrameSettings& settings) {
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
  std::memcpy(frameData_.mapped, &frame, sizeof(frame));
  if (settings.readDrawList && drawListReadback_.size != drawList_.size) {
    vk_.destroyBuffer(drawListReadback_);
    drawListReadback_ = vk_.createBuffer(drawList_.size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
  }

  FrameResult result;
  double period = vk_.timestampPeriod();
  auto start = std::chrono::steady_clock::now();
  if (vk_.isLavapipe() || period == 0.0) {
    // lavapipe's compute timestamps are wrong after the first submission (GPU-NOTES 3): time each
    // submission on the host instead.
    result.timing = "host-per-submission";
    VkCommandBuffer cmd = vk_.beginCommands();
    recordTraversal(cmd, settings);
    vk_.submitAndWait(cmd);
    result.traversalMs = msSince(start);
    auto drawStart = std::chrono::steady_clock::now();
    cmd = vk_.beginCommands();
    recordDraw(cmd, settings);
    vk_.submitAndWait(cmd);
    result.drawMs = msSince(drawStart);
    result.frameMs = msSince(start);
  } else {
    result.timing = "gpu-timestamps";
    VkCommandBuffer cmd = vk_.beginCommands();
    vkCmdResetQueryPool(cmd, queries_, 0, 3);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries_, 0);
    recordTraversal(cmd, settings);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, 1);
    recordDraw(cmd, settings);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, 2);
    vk_.submitAndWait(cmd);
    uint64_t t[3];
    vkCheck(vkGetQueryPoolResults(vk_.device(), queries_, 0, 3, sizeof(t), t, sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
            "vkGetQueryPoolResults");
    result.traversalMs = double(t[1] - t[0]) * period * 1e-6;
    result.drawMs = double(t[2] - t[1]) * period * 1e-6;
    result.frameMs = double(t[2] - t[0]) * period * 1e-6;
  }

  std::memcpy(&result.counters, countersReadback_.mapped, sizeof(result.counters));
  const auto& c = result.counters;
  if (settings.readImage && settings.draw) {
    result.rgba.resize(size_t(width_) * height_ * 4);
    std::memcpy(result.rgba.data(), imageReadback_.mapped, result.rgba.size());
  }
  if (settings.readDrawList) {
    uint32_t n = std::min(c.drawCount, drawCapacity_);
    const uint32_t* p = static_cast<const uint32_t*>(drawListReadback_.mapped);
    result.drawList.resize(n);
    for (uint32_t i = 0; i < n; i++) result.drawList[i] = {p[2 * i], p[2 * i + 1]};
  }
  bool drained = c.itemsDone == c.queueWrite;
  result.complete = c.queueOverflow == 0 && c.drawOverflow == 0 && drained;
  if (!drained && c.queueOverflow == 0)
    throw std::runtime_error("traversal did not drain its queue (" + std::to_string(c.itemsDone) + " of " + std::to_string(c.queueWrite) +
                             " items done, " + std::to_string(c.queueRead) + " claimed; " + std::to_string(c.workgroupsExited) + " of " +
                             std::to_string(persistentWorkgroups_) + " workers left, " + std::to_string(c.budgetExits) + " on their budget)");
  // Grow what overflowed, for the next frame.
  if (c.queueOverflow || c.drawOverflow) {
    uint64_t queueWant = c.queueOverflow ? std::max<uint64_t>(uint64_t(queueCapacity_) * 2, uint64_t(c.queueHighWater) * 5 / 4) : queueCapacity_;
    uint64_t drawWant = c.drawOverflow ? std::max<uint64_t>(uint64_t(drawCapacity_) * 2, uint64_t(c.drawCount) * 5 / 4) : drawCapacity_;
    setCapacities(uint32_t(std::min<uint64_t>(queueWant, UINT32_MAX / 2)), uint32_t(std::min<uint64_t>(drawWant, UINT32_MAX / 2)));
  }
  return result;
}

}  // namespace vgeo
