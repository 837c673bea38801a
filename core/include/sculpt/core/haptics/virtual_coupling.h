#pragma once
// The force a device feels from its proxy: a virtual coupling (Colgate, Stanley
// & Brown 1995), the spring F = k (proxy - device) with damping along the
// contact normal only, limited to what the device can give.
//
// Units: stiffness N/mm, damping N·s/m, forces N; positions in material voxels
// converted with voxel_mm. Order of the limits, each keeping the direction:
//   spring + normal damping -> scaled down to max_force_n -> its growth this
//   tick capped at max_force_step_n (a sudden contact, or material edited
//   under the tool, ramps in over a few ticks instead of kicking).

#include <glm/vec3.hpp>

namespace sculpt::core {

struct CouplingOptions {
  float stiffness_n_per_mm = 1.0f;
  float voxel_mm = 0.5f;
  float damping_ns_per_m = 0.0f;
  float max_force_n = 8.0f;
  /// Largest growth of the force vector in one tick, N.
  float max_force_step_n = 1.0f;
};

class VirtualCoupling {
 public:
  explicit VirtualCoupling(const CouplingOptions& options = {}) : options_(options) {}

  /// The force for this tick. `normal` is the outward contact normal (used
  /// only in contact); `device_velocity_m_per_s` for the damping.
  glm::vec3 force(glm::vec3 proxy_vox, glm::vec3 device_vox, bool contact, glm::vec3 normal,
                  glm::vec3 device_velocity_m_per_s);
  /// The spring alone, before damping and limits: k (proxy - device) voxel_mm.
  glm::vec3 spring_force(glm::vec3 proxy_vox, glm::vec3 device_vox) const;
  /// Forgets the last force (the next one may start at any value).
  void reset() { last_force_n_ = glm::vec3(0.0f); }

  const CouplingOptions& options() const { return options_; }

 private:
  CouplingOptions options_;
  glm::vec3 last_force_n_{0.0f};
};

}  // namespace sculpt::core
