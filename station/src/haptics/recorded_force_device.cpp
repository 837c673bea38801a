#include "sculpt/station/haptics/recorded_force_device.h"

#include "sculpt/hal/types/clock.h"

namespace sculpt::station {

Result<std::optional<RecordedForceDevice>> RecordedForceDevice::from_session(
    const sim::Session& session, const std::string& name, double speed) {
  RecordedForceDevice device;
  bool started = false;
  for (const sim::SessionRecord& r : session.records) {
    if (r.kind != sim::SessionRecord::Kind::kHaptic) continue;
    const sim::HapticRecord& h = r.haptic;
    if (h.type == sim::HapticRecord::Type::kStart && !started) {
      auto setup = parse_loop_setup(h, name);
      if (!setup) return setup.error();
      device.limits_ = setup->limits;
      device.setup_ = *setup;
      started = true;
    }
    if (h.type != sim::HapticRecord::Type::kTick) continue;
    const hal::HapticTickRecord tick = recorded_tick(h);
    // The device was unplugged there: the play ends with it.
    if (tick.read == hal::ForceIo::kRemoved) break;
    device.ticks_.push_back(tick);
  }
  if (device.ticks_.empty()) return std::optional<RecordedForceDevice>();
  const int64_t first_ns = device.ticks_.front().t_ns;
  for (hal::HapticTickRecord& t : device.ticks_)
    t.t_ns -= first_ns;
  device.speed_ = speed > 0.0 ? speed : 1.0;
  device.info_.backend = "sim";
  device.info_.path = name;
  device.info_.name = "recorded force device (" + name + ")";
  return std::optional<RecordedForceDevice>(std::move(device));
}

glm::vec3 RecordedForceDevice::origin_tool_vox() const {
  if (!setup_.placed) return setup_.start_vox;
  // The law's mapping (contact_force_law.h): tool = device * scale / voxel + offset.
  const glm::vec3 device_vox =
      setup_.placed_device_mm * (setup_.contact.workspace_scale / setup_.contact.voxel_mm);
  return setup_.placed_tool_vox - device_vox;
}

hal::ForceIo RecordedForceDevice::read(hal::ForceDeviceState& out) {
  const int64_t now_ns = hal::monotonic_ns();
  if (started_ns_ < 0) started_ns_ = now_ns;
  const double played_ns = static_cast<double>(now_ns - started_ns_) * speed_;
  while (next_ + 1 < ticks_.size() && static_cast<double>(ticks_[next_ + 1].t_ns) <= played_ns)
    ++next_;
  const hal::HapticTickRecord& t = ticks_[next_];
  // Played out: the device goes, as the arm it recorded did.
  if (next_ + 1 == ticks_.size() && static_cast<double>(t.t_ns) <= played_ns)
    return hal::ForceIo::kRemoved;
  out = {t.position_mm, t.buttons, t.homed};
  return t.read;
}

hal::ForceIo RecordedForceDevice::write(glm::vec3 force_n) {
  last_force_n_ = force_n;
  return hal::ForceIo::kOk;
}

}  // namespace sculpt::station
