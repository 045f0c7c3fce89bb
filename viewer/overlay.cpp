// overlay.cpp: Dear ImGui over the swapchain image. The picture is copied into the image first
// (viewer.cpp). The panel alone (one opaque window) is drawn into an image of its own and its rectangle
// copied over the picture; it is drawn again only when what ImGui draws changes (a hash of its lists),
// so a still panel costs a copy: a CPU device (lavapipe) spends milliseconds shading and blending the
// panel's pixels. Anything else (a popup over the picture, the frozen frustum's lines) is drawn straight
// over the picture: a render pass that loads it (LOAD_OP_LOAD from TRANSFER_DST_OPTIMAL) and ends in
// PRESENT_SRC. The panel's vertices are ImGui's own host-visible buffers.
#include "overlay.h"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vgeo {

namespace {
void checkImGuiVk(VkResult r) { vkCheck(r, "Dear ImGui's Vulkan backend"); }

// A render pass of one colour attachment for the panel: over the picture (loads the swapchain image
// the picture was copied into, leaves it presentable) or into the panel's own image (cleared, left
// to be copied from). The two are compatible, so ImGui's one pipeline draws in both.
VkRenderPass createPass(VulkanContext& vk, VkFormat format, bool ownImage) {
  VkAttachmentDescription color{};
  color.format = format;
  color.samples = VK_SAMPLE_COUNT_1_BIT;
  color.loadOp = ownImage ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  color.initialLayout = ownImage ? VK_IMAGE_LAYOUT_UNDEFINED : VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  color.finalLayout = ownImage ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL : VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &ref;
  // Before: the picture's copy (over it), or the last copy out of the panel's image (its own).
  // After: the copy out of the panel's image (the presentation waits on the submission's semaphore).
  // The same for both passes: compatible passes differ only in load, store and layouts.
  VkSubpassDependency deps[2]{};
  deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  deps[0].dstSubpass = 0;
  deps[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  deps[0].srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  deps[1].srcSubpass = 0;
  deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  deps[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  deps[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = 1;
  info.pAttachments = &color;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 2;
  info.pDependencies = deps;
  VkRenderPass pass;
  vkCheck(vkCreateRenderPass(vk.device(), &info, nullptr, &pass), "vkCreateRenderPass (overlay)");
  return pass;
}

// What ImGui draws, as a number: its vertices, indices and commands, and where.
uint64_t hashDrawData(const ImDrawData* data, const VkRect2D& area) {
  uint64_t h = 1469598103934665603ull;
  auto mix = [&h](const void* p, size_t bytes) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (size_t i = 0; i < bytes; i++) h = (h ^ b[i]) * 1099511628211ull;
  };
  mix(&area, sizeof area);
  for (int l = 0; l < data->CmdListsCount; l++) {
    const ImDrawList* list = data->CmdLists[l];
    mix(list->VtxBuffer.Data, size_t(list->VtxBuffer.Size) * sizeof(ImDrawVert));
    mix(list->IdxBuffer.Data, size_t(list->IdxBuffer.Size) * sizeof(ImDrawIdx));
    for (const ImDrawCmd& c : list->CmdBuffer) {
      mix(&c.ClipRect, sizeof c.ClipRect);
      mix(&c.TextureId, sizeof c.TextureId);
      mix(&c.VtxOffset, sizeof c.VtxOffset);
      mix(&c.IdxOffset, sizeof c.IdxOffset);
      mix(&c.ElemCount, sizeof c.ElemCount);
    }
  }
  return h;
}

// The rectangle ImGui draws into ({0,0,1,1} when nothing): each command's vertices within its clip
// rectangle (a clip rectangle alone is often the whole window).
VkRect2D drawnArea(const ImDrawData* data, VkExtent2D extent) {
  float x0 = float(extent.width), y0 = float(extent.height), x1 = 0.0f, y1 = 0.0f;
  for (int l = 0; l < data->CmdListsCount; l++) {
    const ImDrawList* list = data->CmdLists[l];
    for (const ImDrawCmd& c : list->CmdBuffer) {
      if (c.UserCallback) continue;
      float cx0 = c.ClipRect.z, cy0 = c.ClipRect.w, cx1 = c.ClipRect.x, cy1 = c.ClipRect.y;
      for (unsigned i = 0; i < c.ElemCount; i++) {
        const ImVec2 p = list->VtxBuffer[int(c.VtxOffset + list->IdxBuffer[int(c.IdxOffset + i)])].pos;
        cx0 = std::min(cx0, p.x), cy0 = std::min(cy0, p.y), cx1 = std::max(cx1, p.x), cy1 = std::max(cy1, p.y);
      }
      x0 = std::min(x0, std::max(cx0, c.ClipRect.x));
      y0 = std::min(y0, std::max(cy0, c.ClipRect.y));
      x1 = std::max(x1, std::min(cx1, c.ClipRect.z));
      y1 = std::max(y1, std::min(cy1, c.ClipRect.w));
    }
  }
  const ImVec2 scale = data->FramebufferScale, origin = data->DisplayPos;
  VkRect2D area{{0, 0}, {1, 1}};
  if (x1 > x0 && y1 > y0) {
    const int32_t ax = std::clamp(int32_t((x0 - origin.x) * scale.x), 0, int32_t(extent.width) - 1),
                  ay = std::clamp(int32_t((y0 - origin.y) * scale.y), 0, int32_t(extent.height) - 1);
    area.offset = {ax, ay};
    area.extent = {
        uint32_t(std::clamp(int32_t(std::ceil((x1 - origin.x) * scale.x)) - ax, 1, int32_t(extent.width) - ax)),
        uint32_t(std::clamp(int32_t(std::ceil((y1 - origin.y) * scale.y)) - ay, 1, int32_t(extent.height) - ay))};
  }
  return area;
}
}  // namespace

Overlay::Overlay(VulkanContext& vk, GLFWwindow* window, const Swapchain& swapchain) : vk_(vk) {
  overPass_ = createPass(vk_, swapchain.format(), false);
  panelPass_ = createPass(vk_, swapchain.format(), true);
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 8};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  poolInfo.maxSets = 8;
  poolInfo.poolSizeCount = 1;
  poolInfo.pPoolSizes = &size;
  vkCheck(vkCreateDescriptorPool(vk_.device(), &poolInfo, nullptr, &pool_), "vkCreateDescriptorPool (overlay)");

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the working folder
  ImGui::StyleColorsDark();
  ImGui::GetStyle().Colors[ImGuiCol_WindowBg].w = 1.0f;  // opaque: the panel's rectangle is copied over the picture
  ImGui_ImplGlfw_InitForVulkan(window, true);
  ImGui_ImplVulkan_InitInfo init{};
  init.Instance = vk_.instance();
  init.PhysicalDevice = vk_.physicalDevice();
  init.Device = vk_.device();
  init.QueueFamily = vk_.queueFamily();
  init.Queue = vk_.queue();
  init.DescriptorPool = pool_;
  init.MinImageCount = 2;
  init.ImageCount = std::max(swapchain.imageCount(), 2u);
  init.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  init.CheckVkResultFn = checkImGuiVk;
  if (!ImGui_ImplVulkan_Init(&init, overPass_)) throw std::runtime_error("Dear ImGui: the Vulkan backend failed");
  VkCommandBuffer cmd = vk_.beginCommands();
  ImGui_ImplVulkan_CreateFontsTexture(cmd);
  vk_.submitAndWait(cmd);
  ImGui_ImplVulkan_DestroyFontUploadObjects();
  createFramebuffers(swapchain);
}

Overlay::~Overlay() {
  vkDeviceWaitIdle(vk_.device());
  ImGui_ImplVulkan_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  destroyFramebuffers();
  vkDestroyDescriptorPool(vk_.device(), pool_, nullptr);
  vkDestroyRenderPass(vk_.device(), overPass_, nullptr);
  vkDestroyRenderPass(vk_.device(), panelPass_, nullptr);
}

VkFramebuffer Overlay::framebuffer(VkRenderPass pass, VkImageView view) const {
  VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  info.renderPass = pass;
  info.attachmentCount = 1;
  info.pAttachments = &view;
  info.width = extent_.width;
  info.height = extent_.height;
  info.layers = 1;
  VkFramebuffer framebuffer;
  vkCheck(vkCreateFramebuffer(vk_.device(), &info, nullptr, &framebuffer), "vkCreateFramebuffer (overlay)");
  return framebuffer;
}

void Overlay::createFramebuffers(const Swapchain& swapchain) {
  extent_ = swapchain.extent();
  for (uint32_t i = 0; i < swapchain.imageCount(); i++)
    framebuffers_.push_back(framebuffer(overPass_, swapchain.view(i)));
  createImage(vk_, extent_.width, extent_.height, swapchain.format(),
              VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT,
              panelImage_, panelMemory_, panelView_);
  panelFramebuffer_ = framebuffer(panelPass_, panelView_);
  panelDrawn_ = false;
}

void Overlay::destroyFramebuffers() {
  for (VkFramebuffer f : framebuffers_) vkDestroyFramebuffer(vk_.device(), f, nullptr);
  framebuffers_.clear();
  vkDestroyFramebuffer(vk_.device(), panelFramebuffer_, nullptr);
  vkDestroyImageView(vk_.device(), panelView_, nullptr);
  vkDestroyImage(vk_.device(), panelImage_, nullptr);
  vkFreeMemory(vk_.device(), panelMemory_, nullptr);
}

void Overlay::resize(const Swapchain& swapchain) {
  destroyFramebuffers();
  createFramebuffers(swapchain);
}

void Overlay::begin() {
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void Overlay::record(VkCommandBuffer cmd, VkImage swapchainImage, uint32_t image) {
  ImGui::Render();
  const ImDrawData* data = ImGui::GetDrawData();
  // Only where ImGui draws: a CPU device loads and stores every tile a render area covers.
  const VkRect2D area = drawnArea(data, extent_);
  auto draw = [&](VkRenderPass pass, VkFramebuffer target) {
    VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    begin.renderPass = pass;
    begin.framebuffer = target;
    begin.renderArea = area;
    VkClearValue clear{};
    begin.clearValueCount = 1;
    begin.pClearValues = &clear;
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
    vkCmdEndRenderPass(cmd);
  };
  if (data->CmdListsCount != 1) {  // nothing, or more than the panel: straight over the picture
    draw(overPass_, framebuffers_[image]);
    return;
  }
  const uint64_t hash = hashDrawData(data, area);
  if (!panelDrawn_ || hash != panelHash_) draw(panelPass_, panelFramebuffer_);
  panelDrawn_ = true;
  panelHash_ = hash;
  // The picture's copy and the panel's both write the swapchain image: one after the other.
  layoutBarrier(cmd, swapchainImage, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
  VkImageCopy copy{};
  copy.srcSubresource = copy.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.srcOffset = copy.dstOffset = {area.offset.x, area.offset.y, 0};
  copy.extent = {area.extent.width, area.extent.height, 1};
  vkCmdCopyImage(cmd, panelImage_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, swapchainImage,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
  layoutBarrier(cmd, swapchainImage, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0);
}

bool Overlay::wantsMouse() const { return ImGui::GetIO().WantCaptureMouse; }
bool Overlay::wantsKeyboard() const { return ImGui::GetIO().WantCaptureKeyboard; }

}  // namespace vgeo
