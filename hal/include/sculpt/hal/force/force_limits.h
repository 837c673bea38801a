#pragma once
// What a force device can give, per model (DESIGN.md §5a): a data table keyed
// by vendor:product like the quirks table (types/quirks.h), after CHAI3D's
// per-model cHapticDeviceInfo. The haptic loop clamps every force to it and
// the station clamps its stiffness and damping settings to it, whatever the
// user asks for.

#include <cstdint>
#include <span>
#include <string_view>

namespace sculpt::hal {

enum class ForceCapability : uint8_t {
  kForce3,        ///< a force at the end effector (the Falcon)
  kForceTorque6,  ///< force and torque (a 6-DOF arm)
  kEffectBased,   ///< effects the device plays itself (evdev FF_CONSTANT on a joystick)
};

struct ForceLimits {
  uint16_t vendor_id = 0;
  uint16_t product_id = 0;
  std::string_view name;
  ForceCapability capability = ForceCapability::kForce3;
  /// The largest force the device can hold, N.
  float max_force_n = 0.0f;
  /// The stiffest spring it renders without buzzing, N/mm.
  float max_stiffness_n_per_mm = 0.0f;
  /// The most damping it renders without buzzing, N·s/m.
  float max_damping_ns_per_m = 0.0f;
  /// The reach of its end effector from the workspace centre, mm.
  float workspace_radius_mm = 0.0f;

  float clamp_stiffness(float n_per_mm) const;
  float clamp_damping(float ns_per_m) const;
};

/// The limits of vendor:product, or nullptr for a device not in the table.
const ForceLimits* find_force_limits(uint16_t vendor_id, uint16_t product_id);

/// The whole table, for listing and tests.
std::span<const ForceLimits> all_force_limits();

/// The simulated arm's entry (vendor:product 0000:0001), a Falcon's figures.
const ForceLimits& sim_arm_limits();

}  // namespace sculpt::hal
