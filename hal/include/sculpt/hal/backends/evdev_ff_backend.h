#pragma once
// Linux evdev force feedback (HID PID joysticks and wheels, and any other
// /dev/input/eventN whose driver offers FF_CONSTANT) as an effect-based force
// device (DESIGN.md §5a, ForceCapability::kEffectBased).
//
// Implements: listing the event nodes with FF_CONSTANT (nodes this user may
// not open too, from sysfs, with accessible = false); opening one: FF_GAIN,
// FF_AUTOCENTER off, ONE FF_CONSTANT effect uploaded and played, then
// updated in place (EVIOCSFF with the same id, kernel
// Documentation/input/ff.rst "Dynamic update of an effect") only when its
// level or direction changes; the stick's ABS_X/ABS_Y (and ABS_Z) as a
// position in mm and its buttons; unplug as ForceIo::kRemoved.
// Lacks: the condition effects (spring, damper) that some devices render
// on board at a higher rate than 1 kHz; torque; more than two force axes
// (the force's z is ignored); restoring the gain and autocentre the device
// had before (the kernel cannot report them).
//
// Parts (hal/src/backends/evdev_ff/): evdev_io (the ioctl and read/write
// edge, real and faked), constant_effect_mapping (force to level and
// direction, axis to [-1, 1]), evdev_force_device (the ForceDevice),
// evdev_enumeration (listing).
//
// Access: event nodes belong to root:input, mode 0660. The user needs the
// input group or a udev rule with TAG+="uaccess" for the device.
//
// Thread safety: list and open from any thread; the device then belongs to
// its haptic loop (force/force_device.h).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sculpt/base/result.h"
#include "sculpt/hal/force/force_device.h"
#include "sculpt/hal/types/device.h"
#include "sculpt/hal/types/device_info.h"

namespace sculpt::hal {

struct EvdevForceOptions {
  /// The force the effect's full level (0x7fff) stands for at full gain, N:
  /// the device's max_force_n. Stick motors are not calibrated in newtons;
  /// this says what the station's law should take full scale to be.
  float full_scale_n = 4.0f;
  /// Millimetres a stick's half range stands for: an axis at its minimum
  /// reads -workspace_half_range_mm, at its maximum +workspace_half_range_mm,
  /// so the contact law sees mm like on other force devices. Also the
  /// limits' workspace_radius_mm.
  float workspace_half_range_mm = 40.0f;
  /// FF_GAIN, 0..0xffff (ff.rst "Setting the gain"); sent only when the
  /// device declares FF_GAIN. Persists after the device is closed.
  uint16_t gain = 0xffff;
  /// Turn the device's own centring spring off (FF_AUTOCENTER 0) when it has
  /// one: the station's law computes the whole force.
  bool autocenter_off = true;
  /// replay.length of the effect, ms; 0 = play until stopped (see
  /// evdev_force_device.cpp for why that is the default).
  uint16_t effect_length_ms = 0;
  /// The limits a stick renders without buzzing. Guesses, not measured:
  /// full scale over half the half-range, and little damping, because a
  /// USB stick's position is coarse and its effect updates are slow.
  float max_stiffness_n_per_mm = 0.2f;
  float max_damping_ns_per_m = 2.0f;
  /// read() waits up to this long for input when none is pending, ms (0: a
  /// stick that does not move sends nothing, so waiting only costs the tick).
  int read_wait_ms = 0;
};

/// Always kReady on Linux: the kernel interface needs no library.
BackendStatus evdev_ff_backend_status();

/// The event nodes whose device can play FF_CONSTANT (DeviceInfo::backend
/// "evdev-ff", path "/dev/input/eventN", name and vendor:product from the
/// device or sysfs). An Error only when listing itself fails.
Result<std::vector<DeviceInfo>> list_evdev_force_devices();

/// Opens `path` ("/dev/input/eventN") ready for the haptic loop: the effect
/// is uploaded and playing at level 0. Errors name the path and the step
/// that failed; EACCES says how to get access.
Result<std::unique_ptr<ForceDevice>> open_evdev_force_device(const std::string& path,
                                                             const EvdevForceOptions& options = {});

}  // namespace sculpt::hal
