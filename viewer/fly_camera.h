// fly_camera.h: the viewer's camera: a position and a heading (yaw about +y, pitch), moved by keys
// (WASD along and across the view, Q/E down and up) at a speed scaled to the scene, turned by the mouse.
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <optional>

#include "../renderer/camera.h"

namespace vgeo {

struct FlyCamera {
  glm::vec3 eye{0.0f};
  float yaw = 0.0f, pitch = 0.0f;  // radians; yaw 0 looks down -z
  float speed = 1.0f;              // scene units a second
  // The camera it was set to, until it moves: its own eye and target give the very view `vgeo render
  // --camera` makes of them (a target rebuilt from yaw and pitch is off in the last bits).
  std::optional<Camera> exact;

  static FlyCamera from(const Camera& c, float speed) {
    FlyCamera f;
    f.eye = c.eye;
    const glm::vec3 d = glm::normalize(c.target - c.eye);
    f.yaw = std::atan2(d.x, -d.z);
    f.pitch = std::asin(std::clamp(d.y, -1.0f, 1.0f));
    f.speed = speed;
    f.exact = c;
    return f;
  }
  glm::vec3 forward() const {
    return {std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch)};
  }
  // The camera looking along the heading from the eye; the target a unit ahead.
  Camera camera(float fovYDegrees) const {
    if (exact) {
      Camera c = *exact;
      c.fovYDegrees = fovYDegrees;
      return c;
    }
    Camera c;
    c.eye = eye;
    c.target = eye + forward();
    c.fovYDegrees = fovYDegrees;
    return c;
  }
  // Moves by `along` (forward), `across` (right) and `up` units of speed x seconds.
  void move(float along, float across, float up, float seconds) {
    if (along == 0.0f && across == 0.0f && up == 0.0f) return;
    exact.reset();
    const glm::vec3 f = forward(), right = glm::normalize(glm::vec3(std::cos(yaw), 0.0f, std::sin(yaw)));
    eye += (f * along + right * across + glm::vec3(0.0f, 1.0f, 0.0f) * up) * speed * seconds;
  }
  // Turns by a mouse movement of dx, dy pixels (up looks up), never past straight up or down.
  void turn(double dx, double dy) {
    if (dx == 0.0 && dy == 0.0) return;
    exact.reset();
    constexpr float kRadiansPerPixel = 0.003f;
    yaw += float(dx) * kRadiansPerPixel;
    pitch = std::clamp(pitch - float(dy) * kRadiansPerPixel, -1.55f, 1.55f);
  }
};

}  // namespace vgeo
