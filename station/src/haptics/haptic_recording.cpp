#include "sculpt/station/haptics/haptic_recording.h"

#include <cmath>
#include <cstring>
#include <functional>
#include <string_view>
#include <vector>

namespace sculpt::station {
namespace {

// One setting of the set-up text: its name and where its value lives.
struct Binding {
  std::string_view name;
  std::function<double()> get;
  std::function<bool(double)> set;  // false: out of range
};

Binding real(std::string_view name, float& v) {
  return {name, [&v] { return double(v); },
          [&v](double x) {
            v = static_cast<float>(x);
            return std::isfinite(v);
          }};
}

Binding real(std::string_view name, double& v) {
  return {name, [&v] { return v; },
          [&v](double x) {
            v = x;
            return true;
          }};
}

template <class Int>
Binding integer(std::string_view name, Int& v, double lo, double hi) {
  return {name, [&v] { return double(v); },
          [&v, lo, hi](double x) {
            if (!(x >= lo && x <= hi) || x != std::floor(x)) return false;
            v = static_cast<Int>(x);
            return true;
          }};
}

std::vector<Binding> bindings(HapticLoopSetup& s) {
  core::HapticSettings& h = s.contact.haptic;
  std::vector<Binding> b = {
      real("limits.max_force_n", s.limits.max_force_n),
      real("limits.max_stiffness_n_per_mm", s.limits.max_stiffness_n_per_mm),
      real("limits.max_damping_ns_per_m", s.limits.max_damping_ns_per_m),
      real("limits.workspace_radius_mm", s.limits.workspace_radius_mm),
      real("proxy.radius_vox", h.proxy.radius_vox),
      real("proxy.skin_vox", h.proxy.skin_vox),
      real("proxy.slide_step_vox", h.proxy.slide_step_vox),
      integer("proxy.max_steps", h.proxy.max_steps, 0, 1 << 16),
      real("proxy.friction.static", h.proxy.friction.static_coefficient),
      real("proxy.friction.dynamic", h.proxy.friction.dynamic_coefficient),
      real("coupling.stiffness_n_per_mm", h.coupling.stiffness_n_per_mm),
      real("coupling.voxel_mm", h.coupling.voxel_mm),
      real("coupling.damping_ns_per_m", h.coupling.damping_ns_per_m),
      real("coupling.max_force_n", h.coupling.max_force_n),
      real("coupling.max_force_step_n", h.coupling.max_force_step_n),
      real("passivity_max_damping_ns_per_m", h.passivity_max_damping_ns_per_m),
      real("workspace_scale", s.contact.workspace_scale),
      real("voxel_mm", s.contact.voxel_mm),
      real("force_scale", s.contact.force_scale),
      integer("clutch_buttons", s.contact.clutch_buttons, 0, 4294967295.0),
      integer("patch_level", s.contact.patch_level, 0, 8),
      real("safety.ramp_s", s.loop.safety.ramp_s),
      integer("safety.watchdog_ns", s.loop.safety.watchdog_ns, 0, 1e15),
      integer("late_period_ns", s.loop.late_period_ns, 0, 1e15),
      integer("drop_buttons", s.loop.drop_buttons, 0, 4294967295.0),
      real("start_vox.x", s.start_vox.x),
      real("start_vox.y", s.start_vox.y),
      real("start_vox.z", s.start_vox.z),
      integer("placed", s.placed, 0, 1),
      real("placed_tool_vox.x", s.placed_tool_vox.x),
      real("placed_tool_vox.y", s.placed_tool_vox.y),
      real("placed_tool_vox.z", s.placed_tool_vox.z),
      real("placed_device_mm.x", s.placed_device_mm.x),
      real("placed_device_mm.y", s.placed_device_mm.y),
      real("placed_device_mm.z", s.placed_device_mm.z),
      integer("volume_levels", s.volume_levels, 1, 16),
  };
  return b;
}

uint8_t tick_flags(const hal::HapticTickRecord& t) {
  return static_cast<uint8_t>((t.homed ? sim::kTickHomed : 0) |
                              static_cast<int>(t.read) << sim::kTickReadShift |
                              static_cast<int>(t.request) << sim::kTickRequestShift);
}

}  // namespace

sim::HapticRecord start_record(const HapticLoopSetup& setup) {
  HapticLoopSetup copy = setup;
  sim::HapticSettings settings;
  for (const Binding& b : bindings(copy))
    settings.emplace_back(std::string(b.name), b.get());
  sim::HapticRecord r;
  r.type = sim::HapticRecord::Type::kStart;
  r.settings = sim::haptic_settings_text(settings);
  return r;
}

Result<HapticLoopSetup> parse_loop_setup(const sim::HapticRecord& start, const std::string& name) {
  auto parsed = sim::parse_haptic_settings(start.settings);
  if (const auto* why = std::get_if<std::string>(&parsed))
    return Error(name + ": haptic loop set-up: " + *why);
  HapticLoopSetup setup;
  std::vector<Binding> known = bindings(setup);
  for (const auto& setting : std::get<sim::HapticSettings>(parsed)) {
    const std::string& key = setting.first;
    const double value = setting.second;
    const auto it =
        std::find_if(known.begin(), known.end(), [&](const Binding& b) { return b.name == key; });
    if (it == known.end()) return Error(name + ": haptic loop set-up: unknown setting " + key);
    if (!it->set(value)) {
      return Error(name + ": haptic loop set-up: " + key + " = " + std::to_string(value) +
                   " is out of range");
    }
  }
  return setup;
}

sim::HapticRecord patch_record(uint64_t version, glm::vec3 centre_vox) {
  sim::HapticRecord r;
  r.type = sim::HapticRecord::Type::kPatch;
  r.tag = version;
  std::memcpy(r.values, &centre_vox.x, sizeof(float) * 3);
  return r;
}

sim::HapticRecord tick_record(const hal::HapticTickRecord& t) {
  sim::HapticRecord r;
  r.type = sim::HapticRecord::Type::kTick;
  r.tick_t_ns = t.t_ns;
  r.index = t.index;
  r.buttons = t.buttons;
  r.flags = tick_flags(t);
  r.tag = t.law_inputs;
  const float values[6] = {t.position_mm.x, t.position_mm.y, t.position_mm.z,
                           t.force_n.x,     t.force_n.y,     t.force_n.z};
  std::memcpy(r.values, values, sizeof values);
  return r;
}

hal::HapticTickRecord recorded_tick(const sim::HapticRecord& r) {
  hal::HapticTickRecord t;
  t.t_ns = r.tick_t_ns;
  t.index = r.index;
  t.buttons = r.buttons;
  t.homed = (r.flags & sim::kTickHomed) != 0;
  t.read = static_cast<hal::ForceIo>((r.flags >> sim::kTickReadShift) & 3);
  t.request = static_cast<hal::HapticRequest>(r.flags >> sim::kTickRequestShift);
  t.law_inputs = r.tag;
  t.position_mm = {r.values[0], r.values[1], r.values[2]};
  t.force_n = {r.values[3], r.values[4], r.values[5]};
  return t;
}

}  // namespace sculpt::station
