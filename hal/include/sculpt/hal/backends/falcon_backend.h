#pragma once
// The Novint Falcon (0403:cb48) as a force device, over libusb-1.0, written
// from the published protocol (libnifalcon's, no code taken). Implements:
// listing attached Falcons, opening one (FTDI set-up, firmware upload from
// a file the user supplies, with retries, or none when the firmware already
// runs), homing, the 16-byte packet each tick, encoders to position by the
// delta kinematics and force to motor commands by the transposed Jacobian,
// clamped keeping direction. Lacks: the grip's buttons beyond the standard
// four-button grip, the device's own error reports, several Falcons at once
// in one haptic thread.
//
// Parts (hal/src/backends/falcon/): ftdi_transport (the USB edge),
// falcon_firmware (the upload), falcon_packet (the wire format),
// falcon_kinematics (the mechanism), falcon_device (the ForceDevice).
//
// Built when SCULPT_WITH_LIBUSB is on and libusb-1.0 is found; otherwise
// falcon_backend_status() says kNotBuilt and listing and opening fail saying
// so. Access needs the udev rule hal/udev/71-sculpt-falcon.rules.
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

struct FalconOptions {
  /// The Falcon to open: a DeviceInfo::path from list_falcons() (its USB
  /// location, "1-4.2"), or empty for the first one found.
  std::string path;
  /// The Novint firmware file (station option --falcon-firmware FILE). Not
  /// shipped and never downloaded; needed once per power-up.
  std::string firmware_path;
  /// The firmware's bytes, instead of firmware_path.
  std::vector<uint8_t> firmware;
  /// Whole upload attempts before giving up (uploads fail now and then).
  int firmware_attempts = 10;
};

/// kReady, or kNotBuilt with the option and package that would build it.
BackendStatus falcon_backend_status();

/// The attached Falcons (DeviceInfo::backend "falcon"); an Error only when
/// listing itself fails or the backend is not built.
Result<std::vector<DeviceInfo>> list_falcons();

/// Opens a Falcon ready for the haptic loop (not yet homed: see
/// ForceDeviceState::homed). Errors name the device and the step that failed.
Result<std::unique_ptr<ForceDevice>> open_falcon(const FalconOptions& options);

}  // namespace sculpt::hal
