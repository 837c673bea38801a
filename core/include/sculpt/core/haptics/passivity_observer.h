#pragma once
// An energy (passivity) observer and controller (Hannaford & Ryu 2002). The
// material as the hand meets it must never give back more energy than was put
// in; a sampled spring, a proxy that jumps when material is edited under the
// tool, or a force cap can break that and make contact buzz. The observer
// sums the energy the hand has put into the contact,
//   E += -F · v · dt     (J; F the force on the hand in N, v its velocity in m/s),
// and when E would drop below zero it adds just enough damping, along v and
// at most max_damping_ns_per_m, to bring it back to zero.

#include <glm/vec3.hpp>

namespace sculpt::core {

class PassivityObserver {
 public:
  explicit PassivityObserver(float max_damping_ns_per_m = 20.0f)
      : max_damping_ns_per_m_(max_damping_ns_per_m) {}

  /// The force with the damping it needs; updates the energy.
  glm::vec3 apply(glm::vec3 force_n, glm::vec3 velocity_m_per_s, double dt_s);
  /// Starts over (a new contact).
  void reset() { energy_j_ = 0.0; }

  double energy_j() const { return energy_j_; }
  /// The damping added on the last tick, N·s/m.
  float last_damping_ns_per_m() const { return last_damping_; }

 private:
  float max_damping_ns_per_m_;
  double energy_j_ = 0.0;
  float last_damping_ = 0.0f;
};

}  // namespace sculpt::core
