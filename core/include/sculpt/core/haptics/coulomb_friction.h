#pragma once
// Static and dynamic Coulomb friction on the proxy's motion along the surface,
// as a friction cone around the device (Salisbury et al. 1995; Melder &
// Harwin 2004): with a spring from proxy to device, the tangential force is k
// times the proxy's tangential offset from the device and the normal force is
// k times the device's depth below the proxy, so |F_t| <= mu |F_n| becomes a
// bound on where the proxy may sit.

#include <glm/vec3.hpp>

namespace sculpt::core {

struct CoulombFriction {
  /// Coefficients (unit-free); dynamic <= static.
  float static_coefficient = 0.0f;
  float dynamic_coefficient = 0.0f;

  bool enabled() const { return static_coefficient > 0.0f || dynamic_coefficient > 0.0f; }
};

/// Where the proxy goes along the surface with friction.
///   held         the proxy before this tick (on the surface)
///   frictionless where it would slide to without friction
///   device       the device, below the surface
///   normal       the outward unit normal at `held`
///   sliding      in: whether it slid last tick; out: whether it slides now
/// Stuck (not sliding, or dynamic friction enough), the proxy stays at `held`
/// while its tangential offset from the device is within mu * depth; sliding,
/// it trails the frictionless point by mu_d * depth.
glm::vec3 apply_coulomb_friction(const CoulombFriction& friction, glm::vec3 held,
                                 glm::vec3 frictionless, glm::vec3 device, glm::vec3 normal,
                                 bool& sliding);

}  // namespace sculpt::core
