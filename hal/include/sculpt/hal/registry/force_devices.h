#pragma once
// Opening a force device by the id the user gives (`sculpt run --haptic ID`,
// DESIGN.md §7):
//   sim-arm:FILE   the simulated arm (force/sim_arm.h) held by the hand
//                  script in FILE (force/hand_script.h), ticking in real time
//
// Errors name the id and what is wrong, in one line.

#include <memory>
#include <string>

#include "sculpt/base/result.h"
#include "sculpt/hal/force/force_device.h"

namespace sculpt::hal {

Result<std::unique_ptr<ForceDevice>> open_force_device(const std::string& id);

}  // namespace sculpt::hal
