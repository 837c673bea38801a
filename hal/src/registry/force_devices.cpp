#include "sculpt/hal/registry/force_devices.h"

#include "sculpt/hal/force/sim_arm.h"

namespace sculpt::hal {

Result<std::unique_ptr<ForceDevice>> open_force_device(const std::string& id) {
  constexpr std::string_view kSimArm = "sim-arm:";
  if (id.rfind(kSimArm, 0) == 0) {
    auto hand = read_hand_script(id.substr(kSimArm.size()));
    if (!hand) return hand.error().in("--haptic " + id);
    return std::unique_ptr<ForceDevice>(std::make_unique<SimArm>(std::move(hand).value()));
  }
  return Error("--haptic " + id + ": unknown force device (sim-arm:HAND_SCRIPT)");
}

}  // namespace sculpt::hal
