#pragma once
// A force device that plays back the readings a session recorded of one
// (haptic_recording.h), in real time: `sculpt run --device sim:touch.scs`
// plays the session's commands as its device and this as its force device,
// so the station's loop runs live on the recorded hand and the window shows
// the device point, the proxy and the force as they were. When the readings
// run out the device is removed, as the simulated arm is at its unplug.
//
// Thread safety: one thread (the haptic loop's), as any ForceDevice.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sculpt/hal/force/force_device.h"
#include "sculpt/hal/haptics/haptic_loop.h"
#include "sculpt/sim/session/session.h"
#include "sculpt/station/haptics/haptic_recording.h"

namespace sculpt::station {

class RecordedForceDevice final : public hal::ForceDevice {
 public:
  /// The session's recorded device, or nothing when it recorded no force
  /// device. `speed`: 1 plays in real time. Errors: a loop set-up that does
  /// not parse (naming `name`).
  static Result<std::optional<RecordedForceDevice>> from_session(const sim::Session& session,
                                                                 const std::string& name,
                                                                 double speed);

  const hal::DeviceInfo& info() const override { return info_; }
  const hal::ForceLimits& limits() const override { return limits_; }
  hal::ForceIo read(hal::ForceDeviceState& out) override;
  hal::ForceIo write(glm::vec3 force_n) override;
  void zero() noexcept override { last_force_n_ = glm::vec3(0.0f); }

  size_t readings() const { return ticks_.size(); }
  /// The first recorded loop's set-up: the contact to play it with.
  const HapticLoopSetup& setup() const { return setup_; }
  /// Where that loop had the tool when the device was at its origin.
  glm::vec3 origin_tool_vox() const;
  glm::vec3 last_force_n() const { return last_force_n_; }

 private:
  RecordedForceDevice() = default;
  hal::DeviceInfo info_;
  hal::ForceLimits limits_;
  HapticLoopSetup setup_;
  std::vector<hal::HapticTickRecord> ticks_;  // in recorded order, times from 0
  double speed_ = 1.0;
  size_t next_ = 0;
  int64_t started_ns_ = -1;
  glm::vec3 last_force_n_{0.0f};
};

}  // namespace sculpt::station
