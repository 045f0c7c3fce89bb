// camera.h: cameras and the view constants the passes need (camera.cpp).
#pragma once

#include <glm/glm.hpp>

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
// Looks at the scene's bounding sphere from above and to the side, framing all of it; a flat scene
// (a grid of instances) is seen from low over its near corner, so that distance shows in the picture.
Camera defaultCamera(glm::vec4 bounds, glm::vec3 boxMin, glm::vec3 boxMax, float fovYDegrees);

}  // namespace vgeo
