#include "sculpt/station/haptics/haptic_replay.h"

#include <algorithm>
#include <cstring>
#include <utility>

#include <glm/geometric.hpp>

namespace sculpt::station {
namespace {

// Patches a tick may still refer to: the loop reads the newest, at most a
// poll or two behind the recording's newest.
constexpr size_t kPatchesKept = 8;

bool same_bits(glm::vec3 a, glm::vec3 b) {
  return std::memcmp(&a.x, &b.x, sizeof(float) * 3) == 0;
}

}  // namespace

// The device of a replayed loop: it reads what the recording says the live
// device read; what the loop writes is in the loop's last() record.
class HapticReplay::Device final : public hal::ForceDevice {
 public:
  explicit Device(const hal::ForceLimits& limits) : limits_(limits) {
    info_.backend = "replay";
    info_.name = "recorded force device";
  }
  const hal::DeviceInfo& info() const override { return info_; }
  const hal::ForceLimits& limits() const override { return limits_; }
  hal::ForceIo read(hal::ForceDeviceState& out) override {
    out = state_;
    return read_;
  }
  hal::ForceIo write(glm::vec3) override { return hal::ForceIo::kOk; }
  void zero() noexcept override {}

  void stage(const hal::HapticTickRecord& tick) {
    state_ = {tick.position_mm, tick.buttons, tick.homed};
    read_ = tick.read;
  }

 private:
  hal::DeviceInfo info_;
  hal::ForceLimits limits_;
  hal::ForceDeviceState state_;
  hal::ForceIo read_ = hal::ForceIo::kOk;
};

struct HapticReplay::Loop {
  Loop(const HapticLoopSetup& s, int64_t number_)
      : setup(s),
        number(number_),
        device(s.limits),
        sphere(core::sphere_patch(s.contact.haptic.proxy.radius_vox, s.volume_levels)),
        exchange(sphere.options.edge),
        keeper(sphere.options, sphere.level),
        law(exchange, device.limits(), s.contact, s.start_vox),
        loop(device, law, s.loop) {
    if (s.placed) law.place_tool(s.placed_tool_vox, s.placed_device_mm);
  }

  HapticLoopSetup setup;
  int64_t number;
  Device device;
  core::SpherePatch sphere;
  core::PatchExchange exchange;
  core::PatchKeeper keeper;  // no exchange: its patches are kept below
  ContactForceLaw law;
  hal::HapticLoop loop;
  std::deque<core::PatchSnapshot> patches;  // newest last
  uint64_t offered = UINT64_MAX;            // the version in the exchange
  uint32_t next_index = 0;
  bool broken = false;  // a gap: its later ticks cannot be run again
};

HapticReplay::HapticReplay(const StationLoop& material, std::string name)
    : material_(material), name_(std::move(name)) {}

HapticReplay::~HapticReplay() = default;

Status HapticReplay::handle(const sim::HapticRecord& record) {
  switch (record.type) {
    case sim::HapticRecord::Type::kStart: {
      auto setup = parse_loop_setup(record, name_);
      if (!setup) return setup.error();
      if (setup->volume_levels != material_.volume().levels()) {
        return Error(name_ + ": a haptic loop was recorded on a volume of " +
                     std::to_string(setup->volume_levels) + " levels; the replay's has " +
                     std::to_string(material_.volume().levels()));
      }
      loop_ = std::make_unique<Loop>(*setup, figures_.loops++);
      return {};
    }
    case sim::HapticRecord::Type::kPatch: {
      ++figures_.patches;
      if (!loop_) return {};
      const glm::vec3 centre{record.values[0], record.values[1], record.values[2]};
      loop_->keeper.update(material_.volume(), material_.volume_generation(), centre);
      const core::PatchSnapshot& built = loop_->keeper.patch().snapshot();
      if (built.version != record.tag) ++figures_.patch_mismatches;
      loop_->patches.emplace_back();
      core::copy_snapshot(built, loop_->patches.back());
      loop_->patches.back().version = record.tag;  // what the ticks name it by
      if (loop_->patches.size() > kPatchesKept) loop_->patches.pop_front();
      return {};
    }
    case sim::HapticRecord::Type::kTick:
      tick(record);
      return {};
  }
  return {};
}

bool HapticReplay::offer_patch(uint64_t version) {
  Loop& l = *loop_;
  if (version == l.offered) return true;
  const core::PatchSnapshot empty;
  const core::PatchSnapshot* found = version == 0 ? &empty : nullptr;
  for (const core::PatchSnapshot& p : l.patches)
    if (p.version == version) found = &p;
  if (found == nullptr) return false;
  core::copy_snapshot(*found, l.exchange.back());
  l.exchange.publish();
  l.offered = version;
  return true;
}

void HapticReplay::tick(const sim::HapticRecord& record) {
  const hal::HapticTickRecord recorded = recorded_tick(record);
  // The live loop's periods, from the recorded times.
  if (have_last_tick_ && recorded.index > 0) {
    const int64_t period_ns = recorded.t_ns - last_tick_ns_;
    const double period_us = static_cast<double>(period_ns) * 1e-3;
    periods_us_.add(period_us);
    // Late as the live loop counted it: by its own set-up's threshold.
    const int64_t late_ns =
        loop_ ? loop_->setup.loop.late_period_ns : hal::HapticLoopOptions{}.late_period_ns;
    if (period_ns > late_ns) ++figures_.late_ticks;
    figures_.worst_period_us = std::max(figures_.worst_period_us, period_us);
  }
  have_last_tick_ = true;
  last_tick_ns_ = recorded.t_ns;
  figures_.max_force_n = std::max(figures_.max_force_n, glm::length(recorded.force_n));

  if (!loop_ || loop_->broken || recorded.index != loop_->next_index) {
    if (loop_) loop_->broken = true;
    ++figures_.unverified_ticks;
    return;
  }
  Loop& l = *loop_;
  const ContactLawInputs inputs = law_inputs(recorded.law_inputs);
  if (!offer_patch(inputs.patch_version)) {
    l.broken = true;
    ++figures_.unverified_ticks;
    return;
  }
  ++l.next_index;
  l.device.stage(recorded);
  l.law.set_clutch(inputs.clutch_key);
  if (recorded.request == hal::HapticRequest::kEnable) l.loop.enable();
  if (recorded.request == hal::HapticRequest::kDrop) l.loop.drop();
  l.loop.tick(recorded.t_ns);

  ReplayedTick replayed;
  replayed.loop = l.number;
  replayed.tick = l.loop.last();
  for (ContactRecord c; l.law.contacts().try_pop(c);)
    replayed.contact = c;
  replayed.matches = same_bits(replayed.tick.force_n, recorded.force_n);
  ++figures_.ticks;
  if (!replayed.matches) ++figures_.force_mismatches;
  if (on_tick) on_tick(replayed);
}

HapticReplayFigures HapticReplay::figures() const {
  HapticReplayFigures f = figures_;
  f.period_p99_us = periods_us_.quantile_us(0.99);
  return f;
}

}  // namespace sculpt::station
