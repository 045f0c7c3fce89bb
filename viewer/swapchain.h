// swapchain.h: the window's swapchain (swapchain.cpp): images the renderer's picture is copied into and
// the overlay drawn over, one frame in flight, remade when the window's size changes or the surface says
// it is out of date.
#pragma once

#include <vulkan/vulkan.h>

#include <vector>

#include "../renderer/vulkan_context.h"

namespace vgeo {

class Swapchain {
 public:
  Swapchain(VulkanContext& vk, uint32_t width, uint32_t height, bool vsync);
  ~Swapchain();
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;

  // Remakes the swapchain for a framebuffer of width x height (after a resize, or when out of date).
  void recreate(uint32_t width, uint32_t height);
  // The next image to draw into, signalling imageReady() when it may be written; false when the
  // swapchain is out of date (recreate it and skip the frame).
  bool acquire(uint32_t& image);
  // Presents `image` once renderDone(image) is signalled; false when the swapchain must be remade.
  bool present(uint32_t image);

  VkFormat format() const { return format_; }
  bool bgra() const { return format_ == VK_FORMAT_B8G8R8A8_UNORM; }  // the picture can be copied in as B, G, R, A
  VkExtent2D extent() const { return extent_; }
  VkImage image(uint32_t i) const { return images_[i]; }
  VkImageView view(uint32_t i) const { return views_[i]; }
  bool copyable() const { return copyable_; }  // its images can be copied out (a picture of the window)
  uint32_t imageCount() const { return uint32_t(images_.size()); }
  VkSemaphore imageReady() const { return imageReady_; }
  // One an image: a presentation's wait is done only once its image is acquired again.
  VkSemaphore renderDone(uint32_t i) const { return renderDone_[i]; }

 private:
  void create(uint32_t width, uint32_t height);
  void destroy();

  VulkanContext& vk_;
  bool vsync_;
  bool copyable_ = false;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkExtent2D extent_{};
  std::vector<VkImage> images_;
  std::vector<VkImageView> views_;
  VkSemaphore imageReady_ = VK_NULL_HANDLE;
  std::vector<VkSemaphore> renderDone_;
};

}  // namespace vgeo
