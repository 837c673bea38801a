#include "sculpt/core/haptics/coulomb_friction.h"

#include <glm/geometric.hpp>

namespace sculpt::core {
namespace {

glm::vec3 tangential(glm::vec3 v, glm::vec3 n) {
  return v - glm::dot(v, n) * n;
}

}  // namespace

glm::vec3 apply_coulomb_friction(const CoulombFriction& friction, glm::vec3 held,
                                 glm::vec3 frictionless, glm::vec3 device, glm::vec3 normal,
                                 bool& sliding) {
  const float depth = glm::dot(held - device, normal);
  if (!friction.enabled() || depth <= 0.0f) {
    sliding = true;
    return frictionless;
  }
  // Staying put is allowed while the spring's tangential part stays inside
  // the cone: static coefficient from rest, dynamic once moving (so a slide
  // ends when the pull drops below the dynamic bound).
  const float mu = sliding ? friction.dynamic_coefficient : friction.static_coefficient;
  const glm::vec3 offset = tangential(held - device, normal);
  const float offset_length = glm::length(offset);
  if (offset_length <= mu * depth) {
    sliding = false;
    return held;
  }
  // Slide: trail the frictionless point by the dynamic cone's radius, on the
  // side the proxy comes from.
  sliding = true;
  const glm::vec3 trail = tangential(held - frictionless, normal);
  const float trail_length = glm::length(trail);
  const float radius = friction.dynamic_coefficient * depth;
  if (trail_length <= radius) return held;
  return frictionless + trail * (radius / trail_length);
}

}  // namespace sculpt::core
