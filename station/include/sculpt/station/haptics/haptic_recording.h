#pragma once
// A force device's loop in a session (DESIGN.md §5a): what the station
// records so that a replay runs the loop again tick by tick and gets the
// same forces, bit for bit.
//
// A loop's force at a tick depends on the device's reading, the patch the
// law read, the clutch key, the enable/drop requests taken, the tick's time,
// and how the loop was set up. The recording holds each of them:
//   start  the set-up (HapticLoopSetup, as text) when a loop starts;
//   patch  each patch the sculpting side published: its version and the
//          centre it was asked for. The replay builds it again from the
//          replayed material, which at that record is what the live
//          sculpting side read (the record follows the commands it had
//          applied);
//   tick   each tick: its time, number, reading, request taken, the law's
//          inputs (patch version, clutch key) and the force written.

#include <string>

#include <glm/vec3.hpp>

#include "sculpt/base/result.h"
#include "sculpt/hal/force/force_limits.h"
#include "sculpt/hal/haptics/haptic_loop.h"
#include "sculpt/sim/session/session.h"
#include "sculpt/station/haptics/contact_force_law.h"

namespace sculpt::station {

/// How a loop was set up: everything its force depends on but the ticks.
struct HapticLoopSetup {
  /// The device's limits (numbers only: a replay needs no limits table).
  hal::ForceLimits limits;
  /// The contact as asked for (the law clamps it to the limits again).
  ContactSettings contact;
  hal::HapticLoopOptions loop;
  /// Where the tool is when the device is at its origin.
  glm::vec3 start_vox{0.0f};
  /// A restarted loop maps the device's position then to the tool's.
  bool placed = false;
  glm::vec3 placed_tool_vox{0.0f};
  glm::vec3 placed_device_mm{0.0f};
  /// Levels of the volume the patch is read from (sphere_patch()).
  int volume_levels = 5;
};

sim::HapticRecord start_record(const HapticLoopSetup& setup);
/// A start record's set-up; errors name `name` and the setting.
Result<HapticLoopSetup> parse_loop_setup(const sim::HapticRecord& start, const std::string& name);

sim::HapticRecord patch_record(uint64_t version, glm::vec3 centre_vox);
sim::HapticRecord tick_record(const hal::HapticTickRecord& tick);
/// The tick a tick record holds.
hal::HapticTickRecord recorded_tick(const sim::HapticRecord& record);

}  // namespace sculpt::station
