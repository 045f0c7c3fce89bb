// swapchain.cpp: the window's swapchain. The renderer's picture is RGBA8 UNORM; an UNORM swapchain
// format takes its bytes as they are (an sRGB one would encode them a second time), so the window shows
// the pixels `vgeo render` writes. FIFO presents at the display's rate (vsync); without vsync MAILBOX or
// IMMEDIATE where the surface has them.
#include "swapchain.h"

#include <algorithm>
#include <stdexcept>

namespace vgeo {

Swapchain::Swapchain(VulkanContext& vk, uint32_t width, uint32_t height, bool vsync) : vk_(vk), vsync_(vsync) {
  VkSemaphoreCreateInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  vkCheck(vkCreateSemaphore(vk_.device(), &info, nullptr, &imageReady_), "vkCreateSemaphore");
  create(width, height);
}

Swapchain::~Swapchain() {
  vkDeviceWaitIdle(vk_.device());
  destroy();
  vkDestroySemaphore(vk_.device(), imageReady_, nullptr);
}

void Swapchain::create(uint32_t width, uint32_t height) {
  VkPhysicalDevice physical = vk_.physicalDevice();
  VkSurfaceKHR surface = vk_.surface();
  VkSurfaceCapabilitiesKHR caps;
  vkCheck(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(physical, surface, &caps),
          "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
  if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
    throw std::runtime_error("vulkan: the window's images cannot be copied into (no TRANSFER_DST usage)");
  uint32_t count = 0;
  vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &count, nullptr);
  std::vector<VkSurfaceFormatKHR> formats(count);
  vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &count, formats.data());
  if (formats.empty()) throw std::runtime_error("vulkan: the window's surface offers no format");
  VkSurfaceFormatKHR chosen = formats[0];
  for (const VkSurfaceFormatKHR& f : formats)
    if (f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM) {
      chosen = f;
      break;
    }
  vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface, &count, nullptr);
  std::vector<VkPresentModeKHR> modes(count);
  vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface, &count, modes.data());
  VkPresentModeKHR mode = VK_PRESENT_MODE_FIFO_KHR;  // always there
  if (!vsync_)
    for (VkPresentModeKHR m : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
      if (std::find(modes.begin(), modes.end(), m) != modes.end()) {
        mode = m;
        break;
      }
  extent_ = caps.currentExtent;
  if (extent_.width == UINT32_MAX)  // the surface takes the swapchain's size
    extent_ = {std::clamp(width, caps.minImageExtent.width, caps.maxImageExtent.width),
               std::clamp(height, caps.minImageExtent.height, caps.maxImageExtent.height)};
  format_ = chosen.format;
  VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  info.surface = surface;
  info.minImageCount = std::max(caps.minImageCount, 2u);
  if (caps.maxImageCount) info.minImageCount = std::min(info.minImageCount, caps.maxImageCount);
  info.imageFormat = chosen.format;
  info.imageColorSpace = chosen.colorSpace;
  info.imageExtent = extent_;
  info.imageArrayLayers = 1;
  // Copied into, drawn over, and copied out of for a picture of the window (where the surface allows).
  copyable_ = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;
  info.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
                    (copyable_ ? VkImageUsageFlags(VK_IMAGE_USAGE_TRANSFER_SRC_BIT) : 0u);
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = caps.currentTransform;
  info.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                            ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                            : VkCompositeAlphaFlagBitsKHR(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
  info.presentMode = mode;
  info.clipped = VK_TRUE;
  vkCheck(vkCreateSwapchainKHR(vk_.device(), &info, nullptr, &swapchain_), "vkCreateSwapchainKHR");
  vkGetSwapchainImagesKHR(vk_.device(), swapchain_, &count, nullptr);
  images_.resize(count);
  vkGetSwapchainImagesKHR(vk_.device(), swapchain_, &count, images_.data());
  for (VkImage image : images_) {
    VkImageViewCreateInfo v{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    v.image = image;
    v.viewType = VK_IMAGE_VIEW_TYPE_2D;
    v.format = format_;
    v.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view;
    vkCheck(vkCreateImageView(vk_.device(), &v, nullptr, &view), "vkCreateImageView (swapchain)");
    views_.push_back(view);
    VkSemaphoreCreateInfo semaphore{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    renderDone_.push_back(VK_NULL_HANDLE);
    vkCheck(vkCreateSemaphore(vk_.device(), &semaphore, nullptr, &renderDone_.back()), "vkCreateSemaphore");
  }
}

void Swapchain::destroy() {
  for (VkImageView v : views_) vkDestroyImageView(vk_.device(), v, nullptr);
  for (VkSemaphore s : renderDone_) vkDestroySemaphore(vk_.device(), s, nullptr);
  views_.clear();
  renderDone_.clear();
  images_.clear();
  if (swapchain_) vkDestroySwapchainKHR(vk_.device(), swapchain_, nullptr);
  swapchain_ = VK_NULL_HANDLE;
}

void Swapchain::recreate(uint32_t width, uint32_t height) {
  vkDeviceWaitIdle(vk_.device());
  destroy();
  create(width, height);
}

bool Swapchain::acquire(uint32_t& image) {
  VkResult r = vkAcquireNextImageKHR(vk_.device(), swapchain_, UINT64_MAX, imageReady_, VK_NULL_HANDLE, &image);
  if (r == VK_ERROR_OUT_OF_DATE_KHR) return false;
  if (r != VK_SUBOPTIMAL_KHR) vkCheck(r, "vkAcquireNextImageKHR");
  return true;
}

bool Swapchain::present(uint32_t image) {
  VkPresentInfoKHR info{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  info.waitSemaphoreCount = 1;
  info.pWaitSemaphores = &renderDone_[image];
  info.swapchainCount = 1;
  info.pSwapchains = &swapchain_;
  info.pImageIndices = &image;
  VkResult r = vkQueuePresentKHR(vk_.queue(), &info);
  if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) return false;
  vkCheck(r, "vkQueuePresentKHR");
  return true;
}

}  // namespace vgeo
