// viewer.cpp: the viewer's frame, top to bottom: window events and the script's events of this frame,
// the camera moved, the renderer's frame (GpuRenderer::renderFrame, exactly as `vgeo render` runs it),
// its picture copied into the swapchain image, the panel drawn over it, presented. One frame in flight:
// the renderer waits for its own frame anyway, and a screenshot is then the picture just shown.
#include "viewer.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>

#include "../renderer/image.h"
#include "overlay.h"
#include "swapchain.h"
#include "view_state.h"

namespace vgeo {

namespace {

// A window resized by hand settles for this long before the renderer is remade at its size (it is
// remade at once for a scripted resize); meanwhile the last size's picture is scaled.
constexpr double kResizeSettleSeconds = 0.25;
// The panel's numbers change this often (the frame time averaged over it): readable, and a panel that
// does not change is copied, not drawn again (overlay.cpp).
constexpr double kPanelNumbersSeconds = 0.5;

std::string glfwFailure() {
  const char* description = nullptr;
  glfwGetError(&description);
  return description ? description : "unknown GLFW error";
}

struct Window {
  GLFWwindow* handle = nullptr;
  Window(uint32_t width, uint32_t height, const std::string& title) {
    if (!glfwInit())
      throw NoDisplayError("no display to open a window on (" + glfwFailure() +
                           "); `vgeo render` writes the same pictures to PNG files");
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    handle = glfwCreateWindow(int(width), int(height), ("vgeo view: " + title).c_str(), nullptr, nullptr);
    if (!handle) {
      const std::string why = glfwFailure();
      glfwTerminate();
      throw NoDisplayError("the display refused a window (" + why + "); `vgeo render` writes the same pictures");
    }
  }
  ~Window() {
    glfwDestroyWindow(handle);
    glfwTerminate();
  }
  VkExtent2D framebuffer() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(handle, &w, &h);
    return {uint32_t(std::max(w, 0)), uint32_t(std::max(h, 0))};
  }
};

ContextOptions windowContext(const ViewerOptions& o, GLFWwindow* window) {
  ContextOptions c{o.device, o.validate};
  uint32_t count = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&count);
  if (!names) throw NoDisplayError("GLFW finds no Vulkan surface support (" + glfwFailure() + ")");
  c.instanceExtensions.assign(names, names + count);
  c.createSurface = [window](VkInstance instance) {
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    vkCheck(glfwCreateWindowSurface(instance, window, nullptr, &surface), "glfwCreateWindowSurface");
    return surface;
  };
  return c;
}

// Waits, a second at most, for the window to be minimised (iconified) or not: a window manager does it.
bool awaitIconified(const Window& window, bool iconified) {
  for (int i = 0; i < 100 && bool(glfwGetWindowAttrib(window.handle, GLFW_ICONIFIED)) != iconified; i++)
    glfwWaitEventsTimeout(0.01);
  return bool(glfwGetWindowAttrib(window.handle, GLFW_ICONIFIED)) == iconified;
}

// Copies the renderer's picture into swapchain image `image` (scaled when the window's size is not yet
// the renderer's), to TRANSFER_DST_OPTIMAL for the panel's pass.
void recordCopy(VkCommandBuffer cmd, const GpuRenderer& renderer, VkImageLayout pictureLayout, bool bgraTarget,
                const Swapchain& swapchain, uint32_t image) {
  layoutBarrier(cmd, renderer.colorImage(), VK_IMAGE_ASPECT_COLOR_BIT, pictureLayout,
                VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                    VK_PIPELINE_STAGE_TRANSFER_BIT,
                VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                VK_ACCESS_TRANSFER_READ_BIT);
  layoutBarrier(cmd, swapchain.image(image), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                VK_ACCESS_TRANSFER_WRITE_BIT);
  const VkExtent2D to = swapchain.extent();
  VkImageBlit blit{};
  blit.srcSubresource = blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.srcOffsets[1] = {int32_t(renderer.width()), int32_t(renderer.height()), 1};
  blit.dstOffsets[1] = {int32_t(to.width), int32_t(to.height), 1};
  const bool same = renderer.width() == to.width && renderer.height() == to.height;
  if (bgraTarget) {  // the same size and byte order: a plain copy (a blit converts pixel by pixel)
    VkImageCopy copy{};
    copy.srcSubresource = copy.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.extent = {to.width, to.height, 1};
    vkCmdCopyImage(cmd, renderer.colorImage(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, swapchain.image(image),
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
    return;
  }
  vkCmdBlitImage(cmd, renderer.colorImage(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, swapchain.image(image),
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, same ? VK_FILTER_NEAREST : VK_FILTER_LINEAR);
}

// The window as shown, panel and all (the README's picture): swapchain image `image`, presentable, copied
// into a host-visible buffer and made presentable again.
Buffer recordWindowShot(VkCommandBuffer cmd, VulkanContext& vk, const Swapchain& swapchain, uint32_t image) {
  const VkExtent2D e = swapchain.extent();
  Buffer b = vk.createBuffer(VkDeviceSize(e.width) * e.height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
  layoutBarrier(cmd, swapchain.image(image), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {e.width, e.height, 1};
  vkCmdCopyImageToBuffer(cmd, swapchain.image(image), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, b.buffer, 1, &region);
  layoutBarrier(cmd, swapchain.image(image), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0);
  globalBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                VK_ACCESS_HOST_READ_BIT);
  return b;
}

void writeWindowShot(const std::string& path, const Buffer& b, const Swapchain& swapchain) {
  const VkExtent2D e = swapchain.extent();
  std::vector<uint8_t> rgba(size_t(e.width) * e.height * 4);
  std::memcpy(rgba.data(), b.mapped, rgba.size());
  const bool bgra = swapchain.format() == VK_FORMAT_B8G8R8A8_UNORM || swapchain.format() == VK_FORMAT_B8G8R8A8_SRGB;
  for (size_t i = 0; i < rgba.size(); i += 4) {
    if (bgra) std::swap(rgba[i], rgba[i + 2]);
    rgba[i + 3] = 255;
  }
  writePng(path, e.width, e.height, rgba);
}

}  // namespace

uint32_t runViewer(const RenderScene& scene, const ViewerOptions& o) {
  Window window(o.width, o.height, o.title);
  VulkanContext vk(windowContext(o, window.handle));
  VkExtent2D size = window.framebuffer();
  Swapchain swapchain(vk, size.width, size.height, o.vsync);
  auto renderer = std::make_unique<GpuRenderer>(vk, scene, swapchain.extent().width, swapchain.extent().height);

  ViewState s;
  s.fov = o.camera.fovYDegrees;
  s.home = o.camera;
  s.camera = FlyCamera::from(o.camera, scene.bounds.w * 0.5f);
  s.frame.tau = o.tau;
  s.frame.mode = o.mode;
  // Installed before the panel's, which calls them after its own: scroll sets the speed, keys toggle.
  glfwSetWindowUserPointer(window.handle, &s);
  glfwSetScrollCallback(window.handle, [](GLFWwindow* w, double, double dy) {
    if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse) return;
    static_cast<ViewState*>(glfwGetWindowUserPointer(w))->camera.speed *= std::pow(1.25f, float(dy));
  });
  glfwSetKeyCallback(window.handle, [](GLFWwindow* w, int key, int, int action, int) {
    if (action != GLFW_PRESS || (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard)) return;
    const char* name = glfwGetKeyName(key, 0);
    std::string k = key == GLFW_KEY_ESCAPE ? "Escape"
                    : key == GLFW_KEY_F12  ? "F12"
                    : key == GLFW_KEY_TAB  ? "Tab"
                    : name                 ? name
                                           : "";
    if (k == "=") k = "+";
    if (k.size() == 1) k[0] = char(std::toupper(k[0]));
    pressKey(*static_cast<ViewState*>(glfwGetWindowUserPointer(w)), k);
  });
  Overlay overlay(vk, window.handle, swapchain);
  ViewStats stats;
  stats.device = vk.deviceName();
  stats.lodLevels = scene.maxLevels;
  ViewStats shown;  // what the panel shows: stats as of the last refresh
  struct {
    std::chrono::steady_clock::time_point at;
    double ms = 0.0;
    uint32_t frames = 0;
  } refresh;
  ScriptPlayer player{o.script};
  struct {
    uint32_t frames = 0;
    double loopMs = 0.0, renderMs = 0.0;
  } timed;  // frames after the first few (pipelines and lists warm), for the summary at the end
  auto last = std::chrono::steady_clock::now(), sizeChanged = last;
  double minimisedSeconds = 0.0;
  std::optional<std::chrono::steady_clock::time_point> restoreAt;  // a script's minimise
  double mouseX = 0, mouseY = 0;
  glfwGetCursorPos(window.handle, &mouseX, &mouseY);
  for (uint32_t frame = 0; !glfwWindowShouldClose(window.handle); frame++) {
    glfwPollEvents();
    // 1. The script's events of this frame; a scripted resize is waited for and taken at once.
    uint32_t resizeW = 0, resizeH = 0;
    playEvents(player, frame, s, resizeW, resizeH);
    if (s.quit) break;
    if (resizeW) {
      glfwSetWindowSize(window.handle, int(resizeW), int(resizeH));
      for (int i = 0; i < 200 && (window.framebuffer().width != resizeW || window.framebuffer().height != resizeH);
           i++) {
        glfwWaitEventsTimeout(0.01);
      }
    }
    // 2. Keys and mouse move the camera, unless the panel has them.
    const auto now = std::chrono::steady_clock::now();
    const float seconds = std::min(std::chrono::duration<float>(now - last).count(), 0.25f);
    stats.frameMs = std::chrono::duration<double, std::milli>(now - last).count();
    last = now;
    if (frame > kUntimedFrames) {  // the last frame's whole loop, and its renderer's part
      timed.frames++;
      timed.loopMs += stats.frameMs;
      timed.renderMs += stats.frame.frameMs;
    }
    double x, y;
    glfwGetCursorPos(window.handle, &x, &y);
    if (!overlay.wantsMouse() && glfwGetMouseButton(window.handle, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS)
      s.camera.turn(x - mouseX, y - mouseY);
    mouseX = x;
    mouseY = y;
    if (!overlay.wantsKeyboard()) {
      auto held = [&](int key) { return glfwGetKey(window.handle, key) == GLFW_PRESS ? 1.0f : 0.0f; };
      const float boost = held(GLFW_KEY_LEFT_SHIFT) ? 4.0f : 1.0f;
      s.camera.move((held(GLFW_KEY_W) - held(GLFW_KEY_S)) * boost, (held(GLFW_KEY_D) - held(GLFW_KEY_A)) * boost,
                    (held(GLFW_KEY_E) - held(GLFW_KEY_Q)) * boost, seconds);
    }
    // 3. A minimised window draws nothing until it is back; a new size remakes the swapchain, and the
    // renderer once the size settles.
    if (s.minimiseSeconds > 0.0f) {  // a script's: restored when its time is up
      glfwIconifyWindow(window.handle);
      awaitIconified(window, true);
      restoreAt = now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(s.minimiseSeconds));
      s.minimiseSeconds = 0.0f;
    }
    // Minimised, the frame waits (and takes no script frame) until the window is back.
    auto minimised = [&] {
      size = window.framebuffer();
      return size.width == 0 || size.height == 0 || glfwGetWindowAttrib(window.handle, GLFW_ICONIFIED);
    };
    while (minimised() && !glfwWindowShouldClose(window.handle)) {
      const auto from = std::chrono::steady_clock::now();
      if (restoreAt && from >= *restoreAt) {
        glfwRestoreWindow(window.handle);
        awaitIconified(window, false);
        restoreAt.reset();
      } else if (restoreAt) {
        glfwWaitEventsTimeout(std::chrono::duration<double>(*restoreAt - from).count());
      } else {
        glfwWaitEvents();
      }
      minimisedSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - from).count();
      last = std::chrono::steady_clock::now();
    }
    if (glfwWindowShouldClose(window.handle)) break;
    restoreAt.reset();  // no window manager minimised it
    if (size.width != swapchain.extent().width || size.height != swapchain.extent().height) {
      swapchain.recreate(size.width, size.height);
      overlay.resize(swapchain);
      sizeChanged = now;
    }
    const VkExtent2D target = swapchain.extent();
    if ((target.width != renderer->width() || target.height != renderer->height()) &&
        (resizeW || std::chrono::duration<double>(now - sizeChanged).count() > kResizeSettleSeconds)) {
      renderer.reset();
      renderer = std::make_unique<GpuRenderer>(vk, scene, target.width, target.height);
    }
    // 4. The renderer's frame, as `vgeo render` runs it; a screenshot is its picture.
    FrameSettings settings = frameSettings(s, scene, renderer->width(), renderer->height());
    settings.bgraTarget = swapchain.bgra() && renderer->width() == target.width && renderer->height() == target.height;
    stats.frame = renderer->renderFrame(settings);
    // A screenshot is of a complete frame, as `vgeo render` writes (an overflow grows the lists first).
    for (int i = 0; i < 12 && settings.readImage && !stats.frame.complete; i++)
      stats.frame = renderer->renderFrame(settings);
    stats.width = renderer->width();
    stats.height = renderer->height();
    if (!s.screenshot.empty()) {
      writePng(s.screenshot, renderer->width(), renderer->height(), stats.frame.rgba);
      stats.lastScreenshot = s.screenshot;
      s.screenshot.clear();
    }
    refresh.ms += stats.frameMs;
    refresh.frames++;
    if (frame == 0 || std::chrono::duration<double>(now - refresh.at).count() >= kPanelNumbersSeconds) {
      shown = stats;
      shown.frameMs = refresh.ms / refresh.frames;
      refresh = {now, 0.0, 0};
    }
    shown.width = stats.width;
    shown.height = stats.height;
    shown.lastScreenshot = stats.lastScreenshot;
    // 5. The picture into the swapchain, the panel over it, presented.
    overlay.begin();
    drawPanel(s, shown);
    if (s.frozen)
      drawFrozenFrustum(settings.cullView, settings.drawView,
                        glm::distance(settings.cullView.eye, glm::vec3(scene.bounds)) + scene.bounds.w);
    uint32_t image = 0;
    if (!swapchain.acquire(image)) {
      ImGui::EndFrame();
      swapchain.recreate(size.width, size.height);
      overlay.resize(swapchain);
      continue;
    }
    VkCommandBuffer cmd = vk.beginCommands();
    recordCopy(cmd, *renderer, settings.readImage ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL : VK_IMAGE_LAYOUT_GENERAL,
               settings.bgraTarget, swapchain, image);
    overlay.record(cmd, swapchain.image(image), image);
    Buffer shot;
    if (!s.windowShot.empty()) {
      if (!swapchain.copyable()) throw std::runtime_error("this display's window images cannot be copied out");
      shot = recordWindowShot(cmd, vk, swapchain, image);
    }
    vk.submitAndWait(cmd, swapchain.imageReady(), VK_PIPELINE_STAGE_TRANSFER_BIT, swapchain.renderDone(image));
    if (shot.buffer) {
      writeWindowShot(s.windowShot, shot, swapchain);
      shot.reset();
      s.windowShot.clear();
    }
    if (!swapchain.present(image)) {
      swapchain.recreate(size.width, size.height);
      overlay.resize(swapchain);
    }
  }
  vkDeviceWaitIdle(vk.device());
  if (timed.frames)
    std::printf(
        "vgeo view: %u frames timed, %.2f ms a frame: the renderer's passes %.2f, the rest (copy, panel, "
        "present, events) %.2f\n",
        timed.frames, timed.loopMs / timed.frames, timed.renderMs / timed.frames,
        (timed.loopMs - timed.renderMs) / timed.frames);
  if (minimisedSeconds > 0.0) std::printf("vgeo view: minimised for %.1f s, nothing drawn\n", minimisedSeconds);
  return vk.validationMessages();
}

}  // namespace vgeo
