#include "sculpt/hal/registry/force_devices.h"

#include "sculpt/hal/backends/evdev_ff_backend.h"
#include "sculpt/hal/backends/falcon_backend.h"
#include "sculpt/hal/force/sim_arm.h"

namespace sculpt::hal {

Result<std::unique_ptr<ForceDevice>> open_force_device(const std::string& id,
                                                       const ForceDeviceOptions& options) {
  constexpr std::string_view kSimArm = "sim-arm:";
  if (id.rfind(kSimArm, 0) == 0) {
    auto hand = read_hand_script(id.substr(kSimArm.size()));
    if (!hand) return hand.error().in("--haptic " + id);
    return std::unique_ptr<ForceDevice>(std::make_unique<SimArm>(std::move(hand).value()));
  }
  if (id == "falcon" || id.rfind("falcon:", 0) == 0) {
    FalconOptions falcon;
    if (id.size() > 7) falcon.path = id.substr(7);
    falcon.firmware_path = options.falcon_firmware;
    auto device = open_falcon(falcon);
    if (!device) return device.error().in("--haptic " + id);
    return std::move(device).value();
  }
  constexpr std::string_view kEvdev = "evdev-ff:";
  if (id.rfind(kEvdev, 0) == 0) {
    auto device = open_evdev_force_device(id.substr(kEvdev.size()));
    if (!device) return device.error().in("--haptic " + id);
    return std::move(device).value();
  }
  return Error("--haptic " + id +
               ": unknown force device (falcon[:LOCATION], evdev-ff:/dev/input/eventN or "
               "sim-arm:HAND_SCRIPT)");
}

std::vector<DeviceInfo> list_force_devices(std::vector<std::string>* problems) {
  std::vector<DeviceInfo> found;
  auto falcons = list_falcons();
  if (falcons) {
    found = std::move(falcons).value();
  } else if (problems != nullptr) {
    problems->push_back(falcons.error().message());
  }
  auto sticks = list_evdev_force_devices();
  if (sticks) {
    for (DeviceInfo& d : *sticks)
      found.push_back(std::move(d));
  } else if (problems != nullptr) {
    problems->push_back(sticks.error().message());
  }
  return found;
}

}  // namespace sculpt::hal
