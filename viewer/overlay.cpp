// overlay.cpp: Dear ImGui over the swapchain image. The picture is copied into the image first
// (viewer.cpp), so the render pass loads it (LOAD_OP_LOAD from TRANSFER_DST_OPTIMAL) and ends in
// PRESENT_SRC; the panel's vertices are ImGui's own host-visible buffers.
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
}  // namespace

Overlay::Overlay(VulkanContext& vk, GLFWwindow* window, const Swapchain& swapchain) : vk_(vk) {
  VkAttachmentDescription color{};
  color.format = swapchain.format();
  color.samples = VK_SAMPLE_COUNT_1_BIT;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  color.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;  // the picture copied in, kept
  color.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &ref;
  // The copy's writes before the panel's; the presentation waits on the submission's semaphore.
  VkSubpassDependency dependency{};
  dependency.srcSubpass = VK_SUBPASS_EXTERNAL;
  dependency.dstSubpass = 0;
  dependency.srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  dependency.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  dependency.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  dependency.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = 1;
  info.pAttachments = &color;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 1;
  info.pDependencies = &dependency;
  vkCheck(vkCreateRenderPass(vk_.device(), &info, nullptr, &renderPass_), "vkCreateRenderPass (overlay)");

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
  if (!ImGui_ImplVulkan_Init(&init, renderPass_)) throw std::runtime_error("Dear ImGui: the Vulkan backend failed");
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
  vkDestroyRenderPass(vk_.device(), renderPass_, nullptr);
}

void Overlay::createFramebuffers(const Swapchain& swapchain) {
  extent_ = swapchain.extent();
  for (uint32_t i = 0; i < swapchain.imageCount(); i++) {
    VkImageView view = swapchain.view(i);
    VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    info.renderPass = renderPass_;
    info.attachmentCount = 1;
    info.pAttachments = &view;
    info.width = extent_.width;
    info.height = extent_.height;
    info.layers = 1;
    VkFramebuffer framebuffer;
    vkCheck(vkCreateFramebuffer(vk_.device(), &info, nullptr, &framebuffer), "vkCreateFramebuffer (overlay)");
    framebuffers_.push_back(framebuffer);
  }
}

void Overlay::destroyFramebuffers() {
  for (VkFramebuffer f : framebuffers_) vkDestroyFramebuffer(vk_.device(), f, nullptr);
  framebuffers_.clear();
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

void Overlay::record(VkCommandBuffer cmd, uint32_t image) {
  ImGui::Render();
  // Only where the panel draws: a CPU device (lavapipe) loads and stores every tile the render area
  // covers, which for the whole window cost as much as the panel itself.
  const ImDrawData* data = ImGui::GetDrawData();
  float x0 = float(extent_.width), y0 = float(extent_.height), x1 = 0.0f, y1 = 0.0f;
  for (int l = 0; l < data->CmdListsCount; l++)
    for (const ImDrawCmd& c : data->CmdLists[l]->CmdBuffer) {
      x0 = std::min(x0, c.ClipRect.x);
      y0 = std::min(y0, c.ClipRect.y);
      x1 = std::max(x1, c.ClipRect.z);
      y1 = std::max(y1, c.ClipRect.w);
    }
  const ImVec2 scale = data->FramebufferScale, origin = data->DisplayPos;
  VkRect2D area{{0, 0}, {1, 1}};  // nothing drawn: the pass only makes the image presentable
  if (x1 > x0 && y1 > y0) {
    const int32_t ax = std::clamp(int32_t((x0 - origin.x) * scale.x), 0, int32_t(extent_.width) - 1),
                  ay = std::clamp(int32_t((y0 - origin.y) * scale.y), 0, int32_t(extent_.height) - 1);
    area.offset = {ax, ay};
    area.extent = {
        uint32_t(std::clamp(int32_t(std::ceil((x1 - origin.x) * scale.x)) - ax, 1, int32_t(extent_.width) - ax)),
        uint32_t(std::clamp(int32_t(std::ceil((y1 - origin.y) * scale.y)) - ay, 1, int32_t(extent_.height) - ay))};
  }
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  begin.renderPass = renderPass_;
  begin.framebuffer = framebuffers_[image];
  begin.renderArea = area;
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
  vkCmdEndRenderPass(cmd);
}

bool Overlay::wantsMouse() const { return ImGui::GetIO().WantCaptureMouse; }
bool Overlay::wantsKeyboard() const { return ImGui::GetIO().WantCaptureKeyboard; }

}  // namespace vgeo
