// camera.h: cameras and the view constants the passes need (camera.cpp).
#pragma once

#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace vgeo {

struct Camera {
  glm::vec3 eye{0.0f, 0.0f, 5.0f};
  glm::vec3 target{0.0f};
  float fovYDegrees = 60.0f;
};

struct View {
  glm::mat4 viewProjection{1.0f};  // Vulkan clip space: y down, depth 0..1
  glm::mat4 view{1.0f};            // world to view space, looking down -z
  glm::vec2 projection{1.0f};      // clip x and y = this * view x and y (the occlusion tests' projection)
  glm::vec4 planes[6];             // world-space frustum planes, normalised, pointing inwards
  glm::vec3 eye{0.0f};
  float projScale = 1.0f;  // height / (2 tan(fovY / 2))
  float znear = 0.01f;     // reversed depth, far plane at infinity
};

// A view of `camera` for a width x height image; near and far planes fit a scene of `bounds` (sphere).
View makeView(const Camera& camera, uint32_t width, uint32_t height, glm::vec4 bounds);
// A camera as --camera takes it: eye, then target, each to float precision ("ex,ey,ez,tx,ty,tz").
std::string cameraOption(const Camera& c);
// Whether every number of the view is finite in float, the precision the shaders use it in (an eye at
// 3e19, or a field of view of 1e-20 degrees, overflows the view-projection into infinities and NaNs).
bool finiteView(const View& v);
// Frames an object from its front (+z), a little from the right and above, its box filling the
// picture of width / height `aspect`; a flat scene (a grid of instances) is seen from low over its near
// corner, so that distance shows in the picture.
Camera defaultCamera(glm::vec4 bounds, glm::vec3 boxMin, glm::vec3 boxMax, float fovYDegrees,
                     float aspect = 16.0f / 9.0f);
// Frames `points` from the front (+z), a little from the right and above, filling 90% of the picture of
// width / height `aspect` along the tighter axis (sceneCamera: an object's own vertices).
Camera framePoints(const std::vector<glm::vec3>& points, float fovYDegrees, float aspect);

}  // namespace vgeo
