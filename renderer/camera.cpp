// camera.cpp: view and projection matrices (Vulkan conventions) and frustum planes extracted from the
// view-projection matrix (Gribb & Hartmann 2001).
#include "camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace vgeo {

View makeView(const Camera& camera, uint32_t width, uint32_t height, glm::vec4 bounds) {
  View v;
  v.eye = camera.eye;
  float fov = glm::radians(camera.fovYDegrees);
  float radius = std::max(bounds.w, 1e-6f);
  float distance = glm::distance(camera.eye, glm::vec3(bounds));
  v.zfar = distance + 2.0f * radius;
  v.znear = std::max(v.zfar * 1e-6f, 1e-6f * radius);
  glm::vec3 forward = glm::normalize(camera.target - camera.eye);
  glm::vec3 up = std::abs(forward.y) > 0.999f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
  glm::mat4 view = glm::lookAtRH(camera.eye, camera.target, up);
  glm::mat4 proj = glm::perspectiveRH_ZO(fov, float(width) / float(height), v.znear, v.zfar);
  proj[1][1] *= -1.0f;  // Vulkan's y points down
  v.viewProjection = proj * view;
  v.projScale = float(height) / (2.0f * std::tan(0.5f * fov));
  glm::mat4 m = glm::transpose(v.viewProjection);  // rows of the matrix
  glm::vec4 planes[6] = {m[3] + m[0], m[3] - m[0], m[3] + m[1], m[3] - m[1], m[2], m[3] - m[2]};
  for (int i = 0; i < 6; i++) v.planes[i] = planes[i] / glm::length(glm::vec3(planes[i]));
  return v;
}

Camera defaultCamera(glm::vec4 bounds, float fovYDegrees) {
  Camera c;
  c.fovYDegrees = fovYDegrees;
  c.target = glm::vec3(bounds);
  float distance = std::max(bounds.w, 1e-6f) / std::sin(0.5f * glm::radians(fovYDegrees)) * 1.05f;
  c.eye = c.target + glm::normalize(glm::vec3(0.55f, 0.6f, 0.9f)) * distance;
  return c;
}

}  // namespace vgeo
