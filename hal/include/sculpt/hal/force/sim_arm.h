#pragma once
// A simulated force device (DESIGN.md §5a, "simulated arm"): a point mass with
// viscous friction, pushed by a scripted hand (force/hand_script.h) and by the
// force the loop writes, in virtual time. It has what makes a real arm hard to
// render stably: a force limit (the motors saturate), encoder quantisation
// (the position comes in steps), and one tick of delay between writing a
// force and the motors giving it. CI closes the haptic loop through it.
//
// Time: each read() is one tick (tick_ns) after the previous one; the physics
// integrates the tick in `substeps` semi-implicit Euler steps. With the
// defaults and the stiffest spring the limits table allows (3 N/mm), the
// contact's natural frequency is sqrt(3000 / 0.15) = 141 rad/s, 0.14 rad a
// tick: the integration is far inside its stable range, so what the tests see
// is the loop's stability, not the integrator's.
//
// Units: mm, N, kg, s.

#include <cstdint>

#include <glm/vec3.hpp>

#include "sculpt/hal/force/force_device.h"
#include "sculpt/hal/force/hand_script.h"

namespace sculpt::hal {

struct SimArmOptions {
  /// The moving mass at the grip, kg (a Falcon's arms and grip: about 0.15).
  float mass_kg = 0.15f;
  /// The mechanism's own viscous friction, N·s/m.
  float damping_ns_per_m = 1.0f;
  /// One encoder count, mm; the position read is a whole number of them.
  float encoder_step_mm = 0.01f;
  int64_t tick_ns = 1'000'000;
  int substeps = 10;
  /// Where the grip starts, mm.
  glm::vec3 start_mm{0.0f};
};

class SimArm final : public ForceDevice {
 public:
  explicit SimArm(HandScript hand, const SimArmOptions& options = {});

  const DeviceInfo& info() const override { return info_; }
  const ForceLimits& limits() const override;
  /// Advances one tick and reads the quantised position; kRemoved from the
  /// script's unplug time on.
  ForceIo read(ForceDeviceState& out) override;
  /// The force the motors give from the tick after next (one tick of delay),
  /// clamped to the limit.
  ForceIo write(glm::vec3 force_n) override;
  void zero() noexcept override;

  /// The simulation's own state, for tests: the exact position and velocity,
  /// the time of the last read, and the force the motors give now.
  glm::vec3 position_mm() const { return position_mm_; }
  glm::vec3 velocity_mm_per_s() const { return velocity_mm_per_s_; }
  double t_s() const {
    return static_cast<double>(ticks_) * static_cast<double>(options_.tick_ns) * 1e-9;
  }
  glm::vec3 motor_force_n() const { return motor_force_n_; }
  const HandScript& hand() const { return hand_; }

 private:
  HandScript hand_;
  SimArmOptions options_;
  DeviceInfo info_;
  int64_t ticks_ = 0;
  bool removed_ = false;
  glm::vec3 position_mm_;
  glm::vec3 velocity_mm_per_s_{0.0f};
  glm::vec3 written_n_{0.0f};      // the last write(), not yet at the motors
  glm::vec3 motor_force_n_{0.0f};  // what the motors give this tick
};

}  // namespace sculpt::hal
