#include "sculpt/core/haptics/passivity_observer.h"

#include <algorithm>

#include <glm/geometric.hpp>

namespace sculpt::core {

glm::vec3 PassivityObserver::apply(glm::vec3 force_n, glm::vec3 velocity_m_per_s, double dt_s) {
  last_damping_ = 0.0f;
  const double speed2 = double(glm::dot(velocity_m_per_s, velocity_m_per_s));
  const double energy = energy_j_ - double(glm::dot(force_n, velocity_m_per_s)) * dt_s;
  if (energy >= 0.0 || speed2 < 1e-12 || dt_s <= 0.0) {
    energy_j_ = energy;
    return force_n;
  }
  // alpha |v|^2 dt dissipates exactly the deficit.
  const double alpha = std::min(-energy / (speed2 * dt_s), double(max_damping_ns_per_m_));
  last_damping_ = float(alpha);
  energy_j_ = energy + alpha * speed2 * dt_s;
  return force_n - float(alpha) * velocity_m_per_s;
}

}  // namespace sculpt::core
