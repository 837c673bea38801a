#pragma once
// A device that pushes back (DESIGN.md §5a): a Novint Falcon, a force-feedback
// joystick, the simulated arm. The haptic loop (hal/haptics/haptic_loop.h)
// drives it once per tick: read() the position, compute the force, write() it.
//
// Units: millimetres in the device's own frame (x right, y up, z toward the
// user, origin at the workspace centre), newtons, seconds.
//
// Thread safety: one thread (the device's haptic loop) calls read(), write()
// and zero(); the device is created elsewhere and handed over.

#include <cstdint>
#include <string>

#include <glm/vec3.hpp>

#include "sculpt/hal/force/force_limits.h"
#include "sculpt/hal/types/device_info.h"

namespace sculpt::hal {

/// One reading of a force device.
struct ForceDeviceState {
  /// Position of the end effector, mm, device frame.
  glm::vec3 position_mm{0.0f};
  /// Buttons held, bit i = button i.
  uint32_t buttons = 0;
  /// False until the device knows where it is (the Falcon after homing): its
  /// position means nothing and the loop writes no force.
  bool homed = true;
};

enum class ForceIo {
  kOk,
  kRemoved,  ///< the device is gone (unplugged); every later call says so too
  kFault,    ///< a transfer failed or the device reported an error; force must drop
};

class ForceDevice {
 public:
  virtual ~ForceDevice() = default;
  virtual const DeviceInfo& info() const = 0;
  virtual const ForceLimits& limits() const = 0;
  /// The newest position and buttons; waits at most about one tick.
  virtual ForceIo read(ForceDeviceState& out) = 0;
  /// Sends `force_n` (already clamped by the loop to limits()). A 6-DOF or
  /// effect-based device maps it to its own output.
  virtual ForceIo write(glm::vec3 force_n) = 0;
  /// Best effort to leave the device with no force (exit, fault, unplug); never throws.
  virtual void zero() noexcept = 0;
};

}  // namespace sculpt::hal
