// vulkan_context.h: the Vulkan device the renderer runs on, and the few helpers every pass needs
// (buffers, one-shot submissions, shader modules, timestamps). Headless unless a window's surface is asked
// for (the viewer): then the queue also presents to it and the device has VK_KHR_swapchain.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace vgeo {

struct ContextOptions {
  std::string deviceSubstring;  // pick the first device whose name contains it; empty: best available
  bool validation = false;      // Khronos validation layer with synchronization validation
  // Device memory to plan with, when less than the device's (0: all of it): scenes are refused as on a
  // GPU of this much memory.
  uint64_t memoryLimitBytes = 0;
  // A window's surface (the viewer): the instance extensions it needs, and what makes it once the
  // instance exists. The context owns the surface.
  std::vector<const char*> instanceExtensions;
  std::function<VkSurfaceKHR(VkInstance)> createSurface;
};

// A pipeline that destroys itself, so that the renderer keeps no list of its pipelines to destroy.
// Move-only; reads as the VkPipeline it holds (VK_NULL_HANDLE until made).
class Pipeline {
 public:
  Pipeline() = default;
  Pipeline(VkDevice device, VkPipeline pipeline) : device_(device), pipeline_(pipeline) {}
  Pipeline(Pipeline&& other) noexcept { *this = std::move(other); }
  Pipeline& operator=(Pipeline&& other) noexcept {
    if (this != &other) {
      reset();
      device_ = other.device_;
      pipeline_ = other.pipeline_;
      other.pipeline_ = VK_NULL_HANDLE;
    }
    return *this;
  }
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;
  ~Pipeline() { reset(); }
  operator VkPipeline() const { return pipeline_; }

 private:
  void reset() {
    if (pipeline_ != VK_NULL_HANDLE) vkDestroyPipeline(device_, pipeline_, nullptr);
    pipeline_ = VK_NULL_HANDLE;
  }
  VkDevice device_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

// A buffer and its memory, freed with it (move-only), so that no owner keeps a list of buffers to
// destroy. Host-visible buffers stay mapped.
struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize size = 0;
  void* mapped = nullptr;

  Buffer() = default;
  Buffer(Buffer&& other) noexcept { *this = std::move(other); }
  Buffer& operator=(Buffer&& other) noexcept {
    if (this != &other) {
      reset();
      std::swap(buffer, other.buffer);
      std::swap(memory, other.memory);
      std::swap(size, other.size);
      std::swap(mapped, other.mapped);
      std::swap(device, other.device);
    }
    return *this;
  }
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  ~Buffer() { reset(); }
  // Frees the buffer now (a list that grows frees the old one before making the larger).
  void reset() {
    if (buffer != VK_NULL_HANDLE) vkDestroyBuffer(device, buffer, nullptr);
    if (memory != VK_NULL_HANDLE) vkFreeMemory(device, memory, nullptr);
    buffer = VK_NULL_HANDLE;
    memory = VK_NULL_HANDLE;
    size = 0;
    mapped = nullptr;
  }

 private:
  friend class VulkanContext;
  VkDevice device = VK_NULL_HANDLE;
};

class VulkanContext {
 public:
  explicit VulkanContext(const ContextOptions& options);
  ~VulkanContext();
  VulkanContext(const VulkanContext&) = delete;
  VulkanContext& operator=(const VulkanContext&) = delete;

  VkInstance instance() const { return instance_; }
  VkSurfaceKHR surface() const { return surface_; }  // VK_NULL_HANDLE when headless
  VkDevice device() const { return device_; }
  VkPhysicalDevice physicalDevice() const { return physical_; }
  VkQueue queue() const { return queue_; }
  uint32_t queueFamily() const { return queueFamily_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  std::string deviceName() const { return properties_.deviceName; }
  std::string driverName() const { return driverName_; }
  bool isLavapipe() const { return driverId_ == VK_DRIVER_ID_MESA_LLVMPIPE; }
  bool tessellation() const { return tessellation_; }              // tessellationShader enabled
  bool pipelineStatistics() const { return pipelineStatistics_; }  // pipelineStatisticsQuery enabled
  // shaderInt64 and shaderBufferInt64Atomics enabled: the software rasterizer's visibility buffer
  bool int64Atomics() const { return int64Atomics_; }
  bool drawIndirectCount() const { return drawIndirectCount_; }  // vkCmdDrawIndirectCount (patch grids)
  bool deviceClock() const { return deviceClock_; }              // VK_KHR_shader_clock's device clock enabled
  bool hasDeviceExtension(const char* name) const;               // the physical device offers it
  // Nanoseconds per timestamp tick; 0 when the queue has no timestamps.
  double timestampPeriod() const { return timestampValidBits_ ? double(properties_.limits.timestampPeriod) : 0.0; }
  // Validation messages seen so far (warnings and errors); each is also printed to stderr.
  uint32_t validationMessages() const { return validationMessages_; }

  // The first memory type among `bits` (VkMemoryRequirements) with every flag of `flags`; throws if none.
  uint32_t memoryType(uint32_t bits, VkMemoryPropertyFlags flags) const;
  // Device-local buffer (usage | transfer dst/src), or host-visible and mapped when `hostVisible`.
  Buffer createBuffer(VkDeviceSize size, VkBufferUsageFlags usage, bool hostVisible = false);
  // The address shaders read a buffer at (made with VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT).
  VkDeviceAddress deviceAddress(const Buffer& buffer) const;
  // The size of the largest device-local memory heap (at most ContextOptions::memoryLimitBytes).
  VkDeviceSize deviceLocalBytes() const;
  // Copies host data into a device-local buffer through a staging buffer (blocking).
  void upload(const Buffer& dst, const void* data, VkDeviceSize size, VkDeviceSize offset = 0);

  VkCommandBuffer beginCommands();
  // Ends, submits and waits for the command buffer (one submission), then frees it; the submission
  // waits for `wait` (at `waitStage`) and signals `signal` where given (the viewer's swapchain).
  void submitAndWait(VkCommandBuffer cmd, VkSemaphore wait = VK_NULL_HANDLE, VkPipelineStageFlags waitStage = 0,
                     VkSemaphore signal = VK_NULL_HANDLE);

  VkShaderModule createShaderModule(const uint32_t* code, size_t bytes);

  static VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                      VkDebugUtilsMessageTypeFlagsEXT types,
                                                      const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);

 private:
  void createInstance(const ContextOptions& options);
  void pickDevice(const ContextOptions& options);
  void createDevice();

  VkInstance instance_ = VK_NULL_HANDLE;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  uint32_t timestampValidBits_ = 0;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  VkDriverId driverId_{};
  bool tessellation_ = false, pipelineStatistics_ = false, deviceClock_ = false, int64Atomics_ = false,
       drawIndirectCount_ = false;
  std::vector<VkExtensionProperties> deviceExtensions_;
  std::string driverName_;
  uint32_t validationMessages_ = 0;
  uint64_t memoryLimitBytes_ = 0;  // ContextOptions::memoryLimitBytes
};

// Throws std::runtime_error naming the call when a Vulkan call fails.
void vkCheck(VkResult result, const char* what);

// Creates a one-level 2D image in device-local memory (optimal tiling) and its view of `aspect`.
void createImage(VulkanContext& vk, uint32_t width, uint32_t height, VkFormat format, VkImageUsageFlags usage,
                 VkImageAspectFlags aspect, VkImage& image, VkDeviceMemory& memory, VkImageView& view);
// Records a barrier that moves the whole of a one-level image (`aspect`) from layout `from` to `to`, after
// `srcAccess` in `srcStage` and before `dstAccess` in `dstStage`.
void layoutBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                   VkPipelineStageFlags srcStage, VkAccessFlags srcAccess, VkPipelineStageFlags dstStage,
                   VkAccessFlags dstAccess);
// Records a memory barrier: `srcAccess` in `srcStage` before `dstAccess` in `dstStage`.
void globalBarrier(VkCommandBuffer cmd, VkPipelineStageFlags srcStage, VkAccessFlags srcAccess,
                   VkPipelineStageFlags dstStage, VkAccessFlags dstAccess);

}  // namespace vgeo
