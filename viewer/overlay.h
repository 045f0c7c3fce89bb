// overlay.h: the viewer's panel, drawn with Dear ImGui (Debian libimgui-dev: its GLFW and Vulkan
// backends) over the swapchain image the picture was copied into; a panel that did not change is copied
// from its last drawing (overlay.cpp).
#pragma once

#include <vulkan/vulkan.h>

#include <vector>

#include "../renderer/vulkan_context.h"
#include "swapchain.h"

struct GLFWwindow;

namespace vgeo {

class Overlay {
 public:
  Overlay(VulkanContext& vk, GLFWwindow* window, const Swapchain& swapchain);
  ~Overlay();
  Overlay(const Overlay&) = delete;
  Overlay& operator=(const Overlay&) = delete;

  // After the swapchain was remade: framebuffers for its images.
  void resize(const Swapchain& swapchain);
  // Starts the panel's frame: ImGui calls follow, then record().
  void begin();
  // Draws the panel over swapchain image number `image`, `swapchainImage` (in TRANSFER_DST_OPTIMAL, the
  // picture copied in by a transfer before), leaving it ready to present.
  void record(VkCommandBuffer cmd, VkImage swapchainImage, uint32_t image);
  // Whether the panel takes the mouse or the keyboard now (the camera then leaves them alone).
  bool wantsMouse() const;
  bool wantsKeyboard() const;

 private:
  void createFramebuffers(const Swapchain& swapchain);
  void destroyFramebuffers();
  VkFramebuffer framebuffer(VkRenderPass pass, VkImageView view) const;

  VulkanContext& vk_;
  VkRenderPass overPass_ = VK_NULL_HANDLE, panelPass_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  std::vector<VkFramebuffer> framebuffers_;
  VkExtent2D extent_{};
  // The panel's own image (the window's size; the panel's rectangle used) and what was drawn in it.
  VkImage panelImage_ = VK_NULL_HANDLE;
  VkDeviceMemory panelMemory_ = VK_NULL_HANDLE;
  VkImageView panelView_ = VK_NULL_HANDLE;
  VkFramebuffer panelFramebuffer_ = VK_NULL_HANDLE;
  bool panelDrawn_ = false;
  uint64_t panelHash_ = 0;
};

}  // namespace vgeo
