#pragma once
// Opening a force device by the id the user gives (`sculpt run --haptic ID`,
// DESIGN.md §7):
//   falcon[:LOCATION]  a Novint Falcon (backends/falcon_backend.h); the first
//                      one found, or the one at that USB location ("1-4.2");
//                      its firmware from ForceDeviceOptions::falcon_firmware
//   evdev-ff:PATH      a force-feedback joystick or wheel (FF_CONSTANT) at the
//                      event node PATH (backends/evdev_ff_backend.h)
//   sim-arm:FILE       the simulated arm (force/sim_arm.h) held by the hand
//                      script in FILE (force/hand_script.h), ticking in real time
//
// Errors name the id and what is wrong, in one line.

#include <memory>
#include <string>
#include <vector>

#include "sculpt/base/result.h"
#include "sculpt/hal/force/force_device.h"
#include "sculpt/hal/types/device_info.h"

namespace sculpt::hal {

struct ForceDeviceOptions {
  /// The Novint firmware file the user supplies (--falcon-firmware); empty:
  /// the Falcon must already run a firmware (it keeps it until unplugged).
  std::string falcon_firmware;
};

Result<std::unique_ptr<ForceDevice>> open_force_device(const std::string& id,
                                                       const ForceDeviceOptions& options = {});

/// The force devices attached (Falcons, force-feedback sticks), for
/// `sculpt devices`; a backend that
/// cannot list says why in `problems`.
std::vector<DeviceInfo> list_force_devices(std::vector<std::string>* problems = nullptr);

}  // namespace sculpt::hal
