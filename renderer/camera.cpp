// camera.cpp: view and projection matrices (Vulkan conventions, reversed infinite depth) and frustum
// planes extracted from the view-projection matrix (Gribb & Hartmann 2001).
#include "camera.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

namespace vgeo {

std::string cameraOption(const Camera& c) {
  char text[256];
  std::snprintf(text, sizeof text, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y,
                c.target.z);
  return text;
}

View makeView(const Camera& camera, uint32_t width, uint32_t height, glm::vec4 bounds) {
  View v;
  v.eye = camera.eye;
  float fov = glm::radians(camera.fovYDegrees);
  float radius = std::max(bounds.w, 1e-6f);
  float distance = glm::distance(camera.eye, glm::vec3(bounds));
  v.znear = std::max(1e-4f * (distance + radius), 1e-6f * radius);
  glm::vec3 forward = glm::normalize(camera.target - camera.eye);
  glm::vec3 up = std::abs(forward.y) > 0.999f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
  glm::mat4 view = glm::lookAtRH(camera.eye, camera.target, up);
  // Reversed depth with an infinite far plane: depth = znear / distance, so float depth keeps its
  // precision all the way out (with standard depth, far surfaces showed through near ones in speckles).
  float f = 1.0f / std::tan(0.5f * fov);
  glm::mat4 proj(0.0f);
  proj[0][0] = f / (float(width) / float(height));
  proj[1][1] = -f;  // Vulkan's y points down
  proj[2][3] = -1.0f;
  proj[3][2] = v.znear;
  v.viewProjection = proj * view;
  v.view = view;
  v.projection = glm::vec2(proj[0][0], proj[1][1]);
  v.projScale = float(height) / (2.0f * std::tan(0.5f * fov));
  glm::mat4 m = glm::transpose(v.viewProjection);  // rows of the matrix
  // Left, right, bottom, top, near; the far plane is at infinity and culls nothing.
  glm::vec4 planes[6] = {m[3] + m[0], m[3] - m[0], m[3] + m[1],
                         m[3] - m[1], m[3] - m[2], glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)};
  for (int i = 0; i < 5; i++) v.planes[i] = planes[i] / glm::length(glm::vec3(planes[i]));
  v.planes[5] = glm::vec4(0.0f, 1.0f, 0.0f, INFINITY);
  return v;
}

bool finiteView(const View& v) {
  auto finite = [](const float* x, int n) {
    for (int i = 0; i < n; i++)
      if (!std::isfinite(x[i])) return false;
    return true;
  };
  return finite(&v.viewProjection[0][0], 16) && finite(&v.view[0][0], 16) && finite(&v.planes[0][0], 20) &&
         finite(&v.eye[0], 3) && finite(&v.projection[0], 2) && std::isfinite(v.projScale) && std::isfinite(v.znear) &&
         v.znear > 0.0f;
}

Camera defaultCamera(glm::vec4 bounds, glm::vec3 boxMin, glm::vec3 boxMax, float fovYDegrees, float aspect) {
  Camera c;
  c.fovYDegrees = fovYDegrees;
  c.target = glm::vec3(bounds);
  glm::vec3 extent = boxMax - boxMin;
  float wide = std::max(extent.x, extent.z);
  if (extent.y < 0.25f * wide) {
    c.eye = glm::vec3(boxMax.x, boxMax.y + 0.12f * wide, boxMax.z) + glm::vec3(0.05f, 0.0f, 0.05f) * wide;
    c.target = glm::vec3(bounds) - glm::vec3(0.1f, 0.0f, 0.1f) * wide;
    return c;
  }
  std::vector<glm::vec3> corners;
  for (int corner = 0; corner < 8; corner++)
    corners.push_back(
        {corner & 1 ? boxMax.x : boxMin.x, corner & 2 ? boxMax.y : boxMin.y, corner & 4 ? boxMax.z : boxMin.z});
  return framePoints(corners, fovYDegrees, aspect);
}

Camera framePoints(const std::vector<glm::vec3>& points, float fovYDegrees, float aspect) {
  // Seen from the front (+z, the glTF convention), a little from the right and above, as near as keeps
  // every point inside 90% of the picture each way, aimed at the middle of the points' box.
  const glm::vec3 back = glm::normalize(glm::vec3(0.35f, 0.35f, 1.0f));  // from the target to the eye
  const glm::vec3 right = glm::normalize(glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), back)), up = glm::cross(back, right);
  const float tanY = std::tan(0.5f * glm::radians(fovYDegrees)) * 0.9f, tanX = tanY * std::max(aspect, 1e-3f);
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::vec3& p : points) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  Camera c;
  c.fovYDegrees = fovYDegrees;
  c.target = points.empty() ? glm::vec3(0.0f) : 0.5f * (lo + hi);
  // A point's depth in front of the eye is distance - dot(o, back); its offsets across must fit that
  // depth's half-width and half-height. The eye also stays a little outside the points.
  float distance = 1e-6f;
  for (const glm::vec3& p : points) {
    const glm::vec3 o = p - c.target;
    const float along = glm::dot(o, back);
    distance = std::max({distance, along + std::abs(glm::dot(o, right)) / tanX,
                         along + std::abs(glm::dot(o, up)) / tanY, along * 1.05f});
  }
  c.eye = c.target + back * distance;
  return c;
}

}  // namespace vgeo
