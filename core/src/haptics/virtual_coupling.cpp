#include "sculpt/core/haptics/virtual_coupling.h"

#include <glm/geometric.hpp>

namespace sculpt::core {

glm::vec3 VirtualCoupling::spring_force(glm::vec3 proxy_vox, glm::vec3 device_vox) const {
  return options_.stiffness_n_per_mm * options_.voxel_mm * (proxy_vox - device_vox);
}

glm::vec3 VirtualCoupling::force(glm::vec3 proxy_vox, glm::vec3 device_vox, bool contact,
                                 glm::vec3 normal, glm::vec3 device_velocity_m_per_s) {
  // Out of contact the proxy follows the device; where it cannot (the patch
  // has not caught up yet) that is no reason to pull the hand.
  glm::vec3 f(0.0f);
  if (contact) {
    f = spring_force(proxy_vox, device_vox);
    // Damping along the normal only: sliding along the surface stays free.
    f -= options_.damping_ns_per_m * glm::dot(device_velocity_m_per_s, normal) * normal;
  }
  const float length = glm::length(f);
  if (length > options_.max_force_n) f *= options_.max_force_n / length;
  // Only growth is capped: letting go must never keep pushing.
  if (glm::length(f) > glm::length(last_force_n_)) {
    const glm::vec3 change = f - last_force_n_;
    const float change_length = glm::length(change);
    if (change_length > options_.max_force_step_n)
      f = last_force_n_ + change * (options_.max_force_step_n / change_length);
  }
  last_force_n_ = f;
  return f;
}

}  // namespace sculpt::core
