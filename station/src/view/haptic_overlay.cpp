#include "sculpt/station/view/haptic_overlay.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace sculpt::station {
namespace {

constexpr int kCircleSegments = 32;
constexpr float kMinForceN = 0.05f;

// Three great circles of a sphere, as segments.
void add_sphere(std::vector<glm::vec3>& out, glm::vec3 c, float r) {
  const float step = 6.2831853f / kCircleSegments;
  for (int axis = 0; axis < 3; ++axis) {
    for (int i = 0; i < kCircleSegments; ++i) {
      const auto point = [&](int k) {
        glm::vec3 p(0.0f);
        p[(axis + 1) % 3] = r * std::cos(step * static_cast<float>(k));
        p[(axis + 2) % 3] = r * std::sin(step * static_cast<float>(k));
        return c + p;
      };
      out.push_back(point(i));
      out.push_back(point(i + 1));
    }
  }
}

// Any unit vector at right angles to the unit vector d.
glm::vec3 perpendicular(glm::vec3 d) {
  const glm::vec3 other = std::abs(d.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(glm::cross(d, other));
}

}  // namespace

HapticOverlay haptic_overlay(const HapticOverlayInput& in) {
  HapticOverlay o;
  const float r = std::max(in.radius_vox, 0.5f);
  add_sphere(o.proxy, in.proxy_vox, r);
  if (glm::length(in.device_vox - in.proxy_vox) >= kGhostSeparationVox)
    add_sphere(o.ghost, in.device_vox, r);
  const float arm = std::max(0.25f * r, 1.0f);
  for (int axis = 0; axis < 3; ++axis) {
    glm::vec3 d(0.0f);
    d[axis] = arm;
    o.device.push_back(in.device_vox - d);
    o.device.push_back(in.device_vox + d);
  }
  const float magnitude = glm::length(in.force_n);
  if (magnitude >= kMinForceN && std::isfinite(magnitude)) {
    const glm::vec3 dir = in.force_n / magnitude;
    const glm::vec3 tail = in.proxy_vox + dir * r;  // from the proxy's surface
    const glm::vec3 tip = tail + dir * (magnitude * in.arrow_vox_per_n);
    const float head = std::min(0.3f * magnitude * in.arrow_vox_per_n, 3.0f);
    const glm::vec3 side = perpendicular(dir);
    const glm::vec3 other = glm::cross(dir, side);
    o.force = {tail, tip};
    for (const glm::vec3 s : {side, -side, other, -other}) {
      o.force.push_back(tip);
      o.force.push_back(tip - dir * head + s * (0.5f * head));
    }
  }
  return o;
}

}  // namespace sculpt::station
