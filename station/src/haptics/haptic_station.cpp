#include "sculpt/station/haptics/haptic_station.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

#include "sculpt/station/app/station_controller.h"

namespace sculpt::station {
namespace {

// The tool moves with the proxy only when it moved this far: a device at
// rest (its encoders flickering by a count) records no commands.
constexpr float kMoveEpsilonVox = 1e-3f;
// A stroke started by pushing past the press threshold goes on while the
// push stays above this share of it.
constexpr float kStrokeHysteresis = 0.5f;

}  // namespace

HapticStation::HapticStation(std::unique_ptr<hal::ForceDevice> device,
                             const HapticStationOptions& options)
    : device_(std::move(device)), options_(options) {
  enabled_.store(options.enabled);
  past_.device = device_->info().name;
}

HapticStation::~HapticStation() {
  stop();
}

void HapticStation::start(glm::vec3 start_vox, float radius_vox) {
  stop_loop();
  start_loop(start_vox, radius_vox);
  thread_->start();
}

void HapticStation::stop() {
  stop_loop();
}

void HapticStation::start_loop(glm::vec3 start_vox, float radius_vox) {
  ContactSettings contact = options_.contact;
  proxy_radius_vox_ = std::max(radius_vox, 0.0f);
  contact.haptic.proxy.radius_vox = proxy_radius_vox_;
  // The patch's level and size for the proxy (patch_keeper.h): a big
  // tool's is read from a coarser level of the pyramid.
  const core::SpherePatch sphere = core::sphere_patch(proxy_radius_vox_, volume_levels_);
  contact.patch_level = sphere.level;
  const core::DistancePatchOptions& patch = sphere.options;
  const int level = sphere.level;
  // A new exchange for the new patch size: the old loop has stopped reading
  // the old one.
  exchange_ = std::make_unique<core::PatchExchange>(patch.edge);
  keeper_ = std::make_unique<core::PatchKeeper>(*exchange_, patch, level);
  law_ = std::make_unique<ContactForceLaw>(*exchange_, device_->limits(), contact, start_vox);
  setup_ = {.limits = device_->limits(),
            .contact = contact,
            .loop = options_.loop,
            .start_vox = start_vox,
            .volume_levels = volume_levels_};
  setup_recorded_ = false;
  law_->set_clutch(clutch_.load());
  loop_ = std::make_unique<hal::HapticLoop>(*device_, *law_, options_.loop);
  if (enabled_.load()) loop_->enable();
  thread_ = std::make_unique<hal::HapticThread>(*loop_, *device_, options_.thread);
  have_contact_ = false;
  contact_.device_vox = contact_.proxy_vox = start_vox;
}

void HapticStation::stop_loop() {
  if (!thread_) return;
  thread_->stop();
  // Keep the stopped loop's counts in the totals.
  const HapticFigures stopped = figures();
  past_ = stopped;
  past_.running = false;
  thread_.reset();
  loop_.reset();
  law_.reset();
}

void HapticStation::restart(float radius_vox) {
  // The tool stays where it is: the new loop's mapping puts the device's
  // present position there.
  const glm::vec3 tool_vox = contact_.device_vox;
  const glm::vec3 device_mm = tick_.position_mm;
  stop_loop();
  start_loop(tool_vox, radius_vox);
  law_->place_tool(tool_vox, device_mm);
  setup_.placed = true;
  setup_.placed_tool_vox = tool_vox;
  setup_.placed_device_mm = device_mm;
  thread_->start();
  ++past_.restarts;
}

void HapticStation::set_contact(const ContactSettings& contact) {
  options_.contact = contact;
  if (law_) restart(proxy_radius_vox_);
}

ContactSettings HapticStation::contact_settings() const {
  return law_ ? law_->settings() : options_.contact;
}

void HapticStation::enable() {
  enabled_.store(true);
  if (loop_) loop_->enable();
}

void HapticStation::drop() {
  enabled_.store(false);
  if (loop_) loop_->drop();
}

void HapticStation::set_clutch(bool held) {
  clutch_.store(held);
  if (law_) law_->set_clutch(held);
}

void HapticStation::sculpting_side(StationController& controller, int64_t now_ns) {
  if (!loop_) return;
  const StationLoop& station = controller.loop();
  // A new tool: a new proxy of its size, the tool staying where it is.
  if (!tool_seen_ || station.tool_version() != tool_version_ ||
      station.volume().levels() != volume_levels_) {
    const float radius = station.tool_size() * 0.5f;
    const bool levels_changed = station.volume().levels() != volume_levels_;
    volume_levels_ = station.volume().levels();
    if (levels_changed || (tool_seen_ && std::abs(radius - proxy_radius_vox_) > 1e-4f))
      restart(radius);
    tool_seen_ = true;
    tool_version_ = station.tool_version();
  }
  // A recording holds loops from their first tick: one that starts now
  // restarts the loop.
  const bool recording = controller.recording();
  if (recording && !recording_) restart(proxy_radius_vox_);
  recording_ = recording;
  if (recording && !setup_recorded_) {
    controller.record_haptic(start_record(setup_), now_ns);
    setup_recorded_ = true;
  }
  // The newest of what the loop did since the last poll.
  for (ContactRecord r; law_->contacts().try_pop(r);) {
    contact_ = r;
    have_contact_ = true;
  }
  for (hal::HapticTickRecord t; loop_->records().try_pop(t);) {
    tick_ = t;
    const bool mode_button = (t.buttons & 2u) != 0;
    if (mode_button && !mode_button_) ++mode_presses_;
    mode_button_ = mode_button;
    if (recording) controller.record_haptic(tick_record(t), now_ns);
  }
  if (have_contact_ && options_.drives_tool) drive_tool(controller, now_ns);
  if (loop_->state() == hal::HapticLoopState::kRemoved) {
    // Unplugged mid-stroke: the stroke ends where it was, nothing jerks.
    if (pressing_) controller.pointer_up(now_ns);
    pressing_ = false;
    gone_.store(true, std::memory_order_release);
  }
  const glm::vec3 centre_vox = contact_.proxy_vox;
  if (keeper_->update(station.volume(), station.volume_generation(), centre_vox) && recording)
    controller.record_haptic(patch_record(keeper_->patch().snapshot().version, centre_vox), now_ns);
}

void HapticStation::drive_tool(StationController& controller, int64_t now_ns) {
  // Button 1 switches between add and subtract, as on a 3D mouse: once per
  // press seen in any tick since the last poll.
  for (; mode_presses_ > 0; --mode_presses_) {
    const core::SculptMode mode = controller.loop().settings().mode;
    controller.set_mode(
        mode == core::SculptMode::kAdd ? core::SculptMode::kSubtract : core::SculptMode::kAdd,
        now_ns);
  }
  const bool button = (tick_.buttons & 1u) != 0 && !contact_.clutched;
  glm::vec3 at = contact_.proxy_vox;
  bool stroke = false;
  bool hold = false;  // stay in the stroke without moving: no dab
  if (button) {
    if (!contact_.contact) {
      stroke = true;  // in free air: sculpt at the tool
    } else if (const auto pressed = core::pressed_dab_position(
                   contact_.proxy_vox, contact_.normal, contact_.force_n, true, options_.press)) {
      stroke = true;
      at = *pressed;
    } else if (pressing_ && glm::dot(contact_.force_n, contact_.normal) >
                                kStrokeHysteresis * options_.press.threshold_n) {
      // Carving takes the material from under the tool, the push drops below
      // the threshold until the hand catches up, and rises again: the
      // stroke goes on through the dip (one stroke, one undo) with the tool
      // held where it last carved, so the dip carves nothing.
      stroke = true;
      hold = true;
    }
  }
  if (!hold && glm::length(at - last_tool_vox_) > kMoveEpsilonVox) {
    controller.pointer_move(at, now_ns);
    last_tool_vox_ = at;
  }
  if (stroke && !pressing_) controller.pointer_down(now_ns);
  if (!stroke && pressing_) controller.pointer_up(now_ns);
  pressing_ = stroke;
}

HapticFigures HapticStation::figures() const {
  HapticFigures f = past_;
  f.patch = keeper_ ? keeper_->figures() : past_.patch;
  if (!loop_ || !thread_) return f;
  const hal::HapticLiveCounters& live = loop_->live();
  f.running = thread_->running();
  f.ticks += live.ticks.load();
  f.late_ticks += live.late_ticks.load();
  f.device_faults += live.device_faults.load();
  f.records_dropped += live.records_dropped.load() + law_->records_dropped();
  f.skipped_deadlines += thread_->skipped_deadlines();
  f.standby_rescues += thread_->standby_rescues();
  f.threads = std::max(f.threads, thread_->threads());
  f.worst_period_us = std::max(f.worst_period_us, double(live.worst_period_us.load()));
  f.max_force_n = std::max(f.max_force_n, live.max_force_n.load());
  f.ramp = live.ramp.load();
  f.realtime = thread_->realtime();
  f.realtime_note = thread_->realtime_note();
  // The loop's own state, readable once its thread has ended.
  if (!f.running) {
    f.watchdog_trips += loop_->safety().counters().watchdog_trips;
    f.period_p50_us = loop_->periods().quantile_us(0.50);
    f.period_p99_us = loop_->periods().quantile_us(0.99);
  }
  return f;
}

}  // namespace sculpt::station
