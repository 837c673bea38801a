#include "sculpt/station/view/orbit_camera.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "sculpt/core/volume/material_bounds.h"

namespace sculpt::station {
namespace {

constexpr float kMaxPitch = 1.5533430f;  // 89 degrees
constexpr float kMinDistance = 1.0f;
constexpr float kMaxDistance = 1.0e5f;

}  // namespace

void OrbitCamera::frame(glm::vec3 lo, glm::vec3 hi) {
  target_ = 0.5f * (lo + hi);
  const float radius = 0.5f * glm::length(hi - lo);
  yaw_ = 0.5f;
  pitch_ = 0.35f;
  // The bounding sphere fits the vertical field of view, with a margin.
  distance_ = std::clamp(1.15f * radius / std::sin(0.5f * kFovY), kMinDistance, kMaxDistance);
}

void OrbitCamera::frame_material(const core::Volume& volume) {
  if (const std::optional<core::Box> bounds = core::material_bounds(volume)) {
    frame(glm::vec3(bounds->lo), glm::vec3(bounds->hi));
  } else {
    frame(glm::vec3(0.0f), glm::vec3(volume.dims()));
  }
}

float OrbitCamera::focal_length_px(float viewport_height) {
  return 0.5f * viewport_height / std::tan(0.5f * kFovY);
}

void OrbitCamera::set(glm::vec3 target, float yaw_rad, float pitch_rad, float distance) {
  target_ = target;
  yaw_ = yaw_rad;
  pitch_ = std::clamp(pitch_rad, -kMaxPitch, kMaxPitch);
  distance_ = std::clamp(distance, kMinDistance, kMaxDistance);
}

void OrbitCamera::orbit(float yaw_rad, float pitch_rad) {
  yaw_ = std::remainder(yaw_ + yaw_rad, 6.2831853f);
  pitch_ = std::clamp(pitch_ + pitch_rad, -kMaxPitch, kMaxPitch);
}

void OrbitCamera::pan(glm::vec2 pixels, float viewport_height) {
  if (viewport_height <= 0) return;
  // World units per pixel at the target's depth.
  const float scale = 2.0f * distance_ * std::tan(0.5f * kFovY) / viewport_height;
  target_ += (-pixels.x * right() + pixels.y * up()) * scale;
}

void OrbitCamera::zoom(float factor) {
  if (!(factor > 0)) return;
  distance_ = std::clamp(distance_ * factor, kMinDistance, kMaxDistance);
}

glm::vec3 OrbitCamera::forward() const {
  // The eye sits at yaw/pitch on a sphere around the target, looking in.
  const glm::vec3 to_eye(std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_),
                         std::cos(pitch_) * std::cos(yaw_));
  return -to_eye;
}

glm::vec3 OrbitCamera::eye() const {
  return target_ - forward() * distance_;
}

glm::vec3 OrbitCamera::right() const {
  return glm::normalize(glm::cross(forward(), glm::vec3(0, 1, 0)));
}

glm::vec3 OrbitCamera::up() const {
  return glm::cross(right(), forward());
}

glm::mat4 OrbitCamera::view() const {
  return glm::lookAt(eye(), target_, glm::vec3(0, 1, 0));
}

glm::mat4 OrbitCamera::projection(float aspect) const {
  const float near_plane = std::max(0.5f, distance_ * 0.01f);
  const float far_plane = distance_ * 10.0f + 1000.0f;
  return glm::perspective(kFovY, std::max(aspect, 1e-3f), near_plane, far_plane);
}

Ray OrbitCamera::ray(glm::vec2 ndc, float aspect) const {
  const float t = std::tan(0.5f * kFovY);
  Ray r;
  r.origin = eye();
  r.direction = glm::normalize(forward() + right() * (ndc.x * t * aspect) + up() * (ndc.y * t));
  return r;
}

}  // namespace sculpt::station
