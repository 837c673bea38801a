// The public entry of the evdev force-feedback backend: the real evdev edge
// under the listing and the device.

#include "sculpt/hal/backends/evdev_ff_backend.h"

#include <utility>

#include "evdev_enumeration.h"
#include "evdev_force_device.h"
#include "linux_evdev_io.h"

namespace sculpt::hal {

BackendStatus evdev_ff_backend_status() {
  return {};
}

Result<std::vector<DeviceInfo>> list_evdev_force_devices() {
  evdev_ff::LinuxEvdevIo io;
  return evdev_ff::list_evdev_force_devices(io);
}

Result<std::unique_ptr<ForceDevice>> open_evdev_force_device(const std::string& path,
                                                             const EvdevForceOptions& options) {
  auto device =
      evdev_ff::EvdevForceDevice::open(std::make_unique<evdev_ff::LinuxEvdevIo>(), path, options);
  if (!device.ok()) return device.error();
  return std::unique_ptr<ForceDevice>(std::move(device).value());
}

}  // namespace sculpt::hal
