// vulkan_context.cpp: instance, device choice, queue, memory and submission helpers.
// Device choice: --device SUBSTRING wins; otherwise a discrete GPU, then integrated, then virtual, then
// a CPU device (Mesa lavapipe, the default when there is no GPU, as in CI).
#include "vulkan_context.h"

#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace vgeo {

namespace {

const char* resultName(VkResult r) {
  switch (r) {
    case VK_ERROR_OUT_OF_HOST_MEMORY:
      return "out of host memory";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY:
      return "out of device memory";
    case VK_ERROR_DEVICE_LOST:
      return "the device was lost (a GPU fault or a reset)";
    case VK_ERROR_INITIALIZATION_FAILED:
      return "initialization failed";
    case VK_ERROR_LAYER_NOT_PRESENT:
      return "a layer is missing";
    case VK_ERROR_EXTENSION_NOT_PRESENT:
      return "an extension is missing";
    case VK_ERROR_FEATURE_NOT_PRESENT:
      return "a feature is missing";
    case VK_ERROR_INCOMPATIBLE_DRIVER:
      return "no compatible driver";
    case VK_TIMEOUT:
      return "timed out";
    default:
      return "failed";
  }
}

// How long one submission may run before the program gives up on the device. lavapipe's slowest
// frames (tau 1e-9 over the default scene) take ~30 s; a fence not signalled in this time is a hang.
constexpr uint64_t kSubmitTimeoutNs = uint64_t(600) * 1000000000ull;

}  // namespace

void vkCheck(VkResult result, const char* what) {
  if (result != VK_SUCCESS)
    throw std::runtime_error(std::string("vulkan: ") + what + ": " + resultName(result) + " (VkResult " +
                             std::to_string(int(result)) + ")");
}

void globalBarrier(VkCommandBuffer cmd, VkPipelineStageFlags srcStage, VkAccessFlags srcAccess,
                   VkPipelineStageFlags dstStage, VkAccessFlags dstAccess) {
  VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  b.srcAccessMask = srcAccess;
  b.dstAccessMask = dstAccess;
  vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 1, &b, 0, nullptr, 0, nullptr);
}

void createImage(VulkanContext& vk, uint32_t width, uint32_t height, VkFormat format, VkImageUsageFlags usage,
                 VkImageAspectFlags aspect, VkImage& image, VkDeviceMemory& memory, VkImageView& view) {
  VkDevice dev = vk.device();
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {width, height, 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage;
  vkCheck(vkCreateImage(dev, &info, nullptr, &image), "vkCreateImage");
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(dev, image, &req);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = vk.memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  vkCheck(vkAllocateMemory(dev, &alloc, nullptr, &memory), "vkAllocateMemory (image)");
  vkCheck(vkBindImageMemory(dev, image, memory, 0), "vkBindImageMemory");
  VkImageViewCreateInfo v{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  v.image = image;
  v.viewType = VK_IMAGE_VIEW_TYPE_2D;
  v.format = format;
  v.subresourceRange = {aspect, 0, 1, 0, 1};
  vkCheck(vkCreateImageView(dev, &v, nullptr, &view), "vkCreateImageView");
}

void layoutBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                   VkPipelineStageFlags srcStage, VkAccessFlags srcAccess, VkPipelineStageFlags dstStage,
                   VkAccessFlags dstAccess) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = srcAccess;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {aspect, 0, 1, 0, 1};
  vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

VKAPI_ATTR VkBool32 VKAPI_CALL VulkanContext::debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                            VkDebugUtilsMessageTypeFlagsEXT,
                                                            const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                            void* user) {
  if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
    static_cast<VulkanContext*>(user)->validationMessages_++;
    std::fprintf(stderr, "validation: %s\n", data->pMessage);
  }
  return VK_FALSE;
}

namespace {

int deviceRank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return 1;
    default:
      return 0;
  }
}

}  // namespace

VulkanContext::VulkanContext(const ContextOptions& options) : memoryLimitBytes_(options.memoryLimitBytes) {
  createInstance(options);
  if (options.createSurface) surface_ = options.createSurface(instance_);
  pickDevice(options);
  createDevice();
}

// The instance, with the validation layer (synchronization validation on) and its messenger when asked.
void VulkanContext::createInstance(const ContextOptions& options) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "vgeo";
  app.apiVersion = VK_API_VERSION_1_2;
  std::vector<const char*> layers, extensions = options.instanceExtensions;
  if (options.validation) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> available(count);
    vkEnumerateInstanceLayerProperties(&count, available.data());
    bool found = false;
    for (auto& l : available) found |= std::strcmp(l.layerName, "VK_LAYER_KHRONOS_validation") == 0;
    if (!found)
      throw std::runtime_error(
          "vulkan: --validate needs VK_LAYER_KHRONOS_validation (Debian: vulkan-validationlayers)");
    layers.push_back("VK_LAYER_KHRONOS_validation");
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;
  VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messengerInfo.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messengerInfo.pfnUserCallback = debugCallback;
  messengerInfo.pUserData = this;
  features.pNext = &messengerInfo;

  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  info.enabledLayerCount = uint32_t(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  if (options.validation) info.pNext = &features;
  vkCheck(vkCreateInstance(&info, nullptr, &instance_),
          "vkCreateInstance (is a Vulkan driver installed? Debian: mesa-vulkan-drivers)");
  if (options.validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    if (create) vkCheck(create(instance_, &messengerInfo, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
  }
}

// The Vulkan 1.2 device named by --device, else the best-ranked kind (deviceRank); its properties, and
// its graphics + compute queue family.
void VulkanContext::pickDevice(const ContextOptions& options) {
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance_, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance_, &count, devices.data());
  if (devices.empty()) throw std::runtime_error("vulkan: no Vulkan device (install mesa-vulkan-drivers for lavapipe)");
  int bestRank = -1;
  std::string names;
  for (VkPhysicalDevice d : devices) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    names += std::string(names.empty() ? "" : ", ") + p.deviceName;
    if (p.apiVersion < VK_API_VERSION_1_2) continue;
    int rank = deviceRank(p.deviceType);
    if (!options.deviceSubstring.empty())
      rank = std::strstr(p.deviceName, options.deviceSubstring.c_str()) ? 100 - int(&d - devices.data()) : -1;
    if (rank > bestRank) {
      bestRank = rank;
      physical_ = d;
    }
  }
  if (!physical_ || bestRank < 0)
    throw std::runtime_error(
        "vulkan: no Vulkan 1.2 device" +
        (options.deviceSubstring.empty() ? std::string() : " named like '" + options.deviceSubstring + "'") +
        " among: " + names);
  vkGetPhysicalDeviceProperties(physical_, &properties_);
  vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  driver.pNext = &subgroup;
  VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props2.pNext = &driver;
  vkGetPhysicalDeviceProperties2(physical_, &props2);
  driverId_ = driver.driverID;
  driverName_ = std::string(driver.driverName) + " " + driver.driverInfo;
  // The persistent traversal adds to shared counters once a subgroup (subgroupExclusiveAdd, elect, broadcast).
  const VkSubgroupFeatureFlags neededSubgroupOps =
      VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_ARITHMETIC_BIT | VK_SUBGROUP_FEATURE_BALLOT_BIT;
  if ((subgroup.supportedOperations & neededSubgroupOps) != neededSubgroupOps ||
      !(subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT))
    throw std::runtime_error("vulkan: " + deviceName() + " lacks subgroup arithmetic and ballot in compute shaders");

  uint32_t families = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &families, nullptr);
  std::vector<VkQueueFamilyProperties> familyProps(families);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &families, familyProps.data());
  queueFamily_ = UINT32_MAX;
  for (uint32_t i = 0; i < families; i++) {
    VkBool32 presents = VK_TRUE;  // to the window's surface, when there is one
    if (surface_) vkGetPhysicalDeviceSurfaceSupportKHR(physical_, i, surface_, &presents);
    if ((familyProps[i].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) ==
            (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT) &&
        presents) {
      queueFamily_ = i;
      timestampValidBits_ = familyProps[i].timestampValidBits;
      break;
    }
  }
  if (queueFamily_ == UINT32_MAX)
    throw std::runtime_error("vulkan: no queue with graphics and compute" +
                             std::string(surface_ ? " that presents to the window" : "") + " on " + deviceName());
}

// The logical device with the optional features the renderer uses where supported, its queue and a
// command pool.
void VulkanContext::createDevice() {
  float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = queueFamily_;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  VkPhysicalDeviceFeatures supported{};
  vkGetPhysicalDeviceFeatures(physical_, &supported);
  VkPhysicalDeviceFeatures enabled{};
  enabled.fillModeNonSolid = supported.fillModeNonSolid;
  enabled.vertexPipelineStoresAndAtomics = supported.vertexPipelineStoresAndAtomics;
  enabled.fragmentStoresAndAtomics = supported.fragmentStoresAndAtomics;
  enabled.tessellationShader = supported.tessellationShader;
  enabled.pipelineStatisticsQuery = supported.pipelineStatisticsQuery;
  tessellation_ = supported.tessellationShader;
  pipelineStatistics_ = supported.pipelineStatisticsQuery;
  uint32_t extensionCount = 0;
  vkEnumerateDeviceExtensionProperties(physical_, nullptr, &extensionCount, nullptr);
  deviceExtensions_.resize(extensionCount);
  vkEnumerateDeviceExtensionProperties(physical_, nullptr, &extensionCount, deviceExtensions_.data());
  // The device clock, where there is one, for the persistent traversal's worker profile (bench only).
  VkPhysicalDeviceShaderClockFeaturesKHR clock{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_CLOCK_FEATURES_KHR};
  if (hasDeviceExtension(VK_KHR_SHADER_CLOCK_EXTENSION_NAME)) {
    VkPhysicalDeviceFeatures2 features2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features2.pNext = &clock;
    vkGetPhysicalDeviceFeatures2(physical_, &features2);
    deviceClock_ = clock.shaderDeviceClock == VK_TRUE;
  }
  // 64-bit buffer atomics, where there are, for the visibility buffer (raster_software.comp).
  VkPhysicalDeviceVulkan12Features vulkan12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  {
    VkPhysicalDeviceFeatures2 features2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features2.pNext = &vulkan12;
    vkGetPhysicalDeviceFeatures2(physical_, &features2);
    int64Atomics_ = supported.shaderInt64 && vulkan12.shaderBufferInt64Atomics;
    drawIndirectCount_ = vulkan12.drawIndirectCount == VK_TRUE;
    // The scene's arrays are read by device address (shaderio_frame.h, SceneArrays).
    if (!vulkan12.bufferDeviceAddress)
      throw std::runtime_error("vulkan: " + deviceName() + " lacks bufferDeviceAddress (Vulkan 1.2)");
    vulkan12 = {VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    vulkan12.shaderBufferInt64Atomics = int64Atomics_;
    vulkan12.drawIndirectCount = drawIndirectCount_;
    vulkan12.bufferDeviceAddress = VK_TRUE;
    enabled.shaderInt64 = int64Atomics_;
  }
  std::vector<const char*> extensions;
  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  deviceInfo.pNext = &vulkan12;
  if (deviceClock_) {  // `clock` holds the supported features: enabled as they are
    vulkan12.pNext = &clock;
    extensions.push_back(VK_KHR_SHADER_CLOCK_EXTENSION_NAME);
  }
  if (surface_) {
    if (!hasDeviceExtension(VK_KHR_SWAPCHAIN_EXTENSION_NAME))
      throw std::runtime_error("vulkan: " + deviceName() + " cannot present to a window (no VK_KHR_swapchain)");
    extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  }
  deviceInfo.enabledExtensionCount = uint32_t(extensions.size());
  deviceInfo.ppEnabledExtensionNames = extensions.data();
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  deviceInfo.pEnabledFeatures = &enabled;
  vkCheck(vkCreateDevice(physical_, &deviceInfo, nullptr, &device_), "vkCreateDevice");
  vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);

  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = queueFamily_;
  vkCheck(vkCreateCommandPool(device_, &poolInfo, nullptr, &pool_), "vkCreateCommandPool");
}

bool VulkanContext::hasDeviceExtension(const char* name) const {
  for (const auto& e : deviceExtensions_)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

VulkanContext::~VulkanContext() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    vkDestroyCommandPool(device_, pool_, nullptr);
    vkDestroyDevice(device_, nullptr);
  }
  if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr);
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
}

uint32_t VulkanContext::memoryType(uint32_t bits, VkMemoryPropertyFlags flags) const {
  for (uint32_t i = 0; i < memory_.memoryTypeCount; i++)
    if ((bits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & flags) == flags) return i;
  throw std::runtime_error("vulkan: no suitable memory type");
}

Buffer VulkanContext::createBuffer(VkDeviceSize size, VkBufferUsageFlags usage, bool hostVisible) {
  Buffer b;
  b.device = device_;
  b.size = std::max<VkDeviceSize>(size, 16);
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = b.size;
  info.usage = usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
  vkCheck(vkCreateBuffer(device_, &info, nullptr, &b.buffer), "vkCreateBuffer");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device_, b.buffer, &req);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
  flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
  if (usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) alloc.pNext = &flags;
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = memoryType(
      req.memoryTypeBits, hostVisible ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                                      : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  VkResult r = vkAllocateMemory(device_, &alloc, nullptr, &b.memory);
  if (r != VK_SUCCESS)  // b frees its buffer on the way out
    throw std::runtime_error("vulkan: out of device memory allocating " + std::to_string(b.size >> 20) + " MiB");
  vkCheck(vkBindBufferMemory(device_, b.buffer, b.memory, 0), "vkBindBufferMemory");
  if (hostVisible) vkCheck(vkMapMemory(device_, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped), "vkMapMemory");
  return b;
}

VkDeviceAddress VulkanContext::deviceAddress(const Buffer& b) const {
  VkBufferDeviceAddressInfo info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
  info.buffer = b.buffer;
  return vkGetBufferDeviceAddress(device_, &info);
}

VkDeviceSize VulkanContext::deviceLocalBytes() const {
  VkDeviceSize largest = 0;
  for (uint32_t i = 0; i < memory_.memoryHeapCount; i++)
    if (memory_.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
      largest = std::max(largest, memory_.memoryHeaps[i].size);
  return memoryLimitBytes_ ? std::min<VkDeviceSize>(largest, memoryLimitBytes_) : largest;
}

void VulkanContext::upload(const Buffer& dst, const void* data, VkDeviceSize size, VkDeviceSize offset) {
  if (size == 0) return;
  Buffer staging = createBuffer(size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
  std::memcpy(staging.mapped, data, size_t(size));
  VkCommandBuffer cmd = beginCommands();
  VkBufferCopy region{0, offset, size};
  vkCmdCopyBuffer(cmd, staging.buffer, dst.buffer, 1, &region);
  submitAndWait(cmd);
}

VkCommandBuffer VulkanContext::beginCommands() {
  VkCommandBufferAllocateInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  info.commandPool = pool_;
  info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  info.commandBufferCount = 1;
  VkCommandBuffer cmd;
  vkCheck(vkAllocateCommandBuffers(device_, &info, &cmd), "vkAllocateCommandBuffers");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkCheck(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
  return cmd;
}

void VulkanContext::submitAndWait(VkCommandBuffer cmd, VkSemaphore wait, VkPipelineStageFlags waitStage,
                                  VkSemaphore signal) {
  vkCheck(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence;
  vkCheck(vkCreateFence(device_, &fenceInfo, nullptr, &fence), "vkCreateFence");
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  if (wait) {
    submit.waitSemaphoreCount = 1;
    submit.pWaitSemaphores = &wait;
    submit.pWaitDstStageMask = &waitStage;
  }
  if (signal) {
    submit.signalSemaphoreCount = 1;
    submit.pSignalSemaphores = &signal;
  }
  vkCheck(vkQueueSubmit(queue_, 1, &submit, fence), "vkQueueSubmit");
  const VkResult waited = vkWaitForFences(device_, 1, &fence, VK_TRUE, kSubmitTimeoutNs);
  if (waited == VK_TIMEOUT)
    throw std::runtime_error("vulkan: a submission did not finish within " +
                             std::to_string(kSubmitTimeoutNs / 1000000000ull) + " s: the device hangs");
  vkCheck(waited, "vkWaitForFences");
  vkDestroyFence(device_, fence, nullptr);
  vkFreeCommandBuffers(device_, pool_, 1, &cmd);
}

VkShaderModule VulkanContext::createShaderModule(const uint32_t* code, size_t bytes) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = bytes;
  info.pCode = code;
  VkShaderModule module;
  vkCheck(vkCreateShaderModule(device_, &info, nullptr, &module), "vkCreateShaderModule");
  return module;
}

}  // namespace vgeo
