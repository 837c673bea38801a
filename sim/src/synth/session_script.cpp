#include "sculpt/sim/synth/session_script.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "sculpt/hal/parsers/make_parser.h"

namespace sculpt::sim {
namespace {

constexpr float kPi = 3.14159265358979f;

}  // namespace

hal::DeviceInfo scripted_device(uint16_t vendor_id, uint16_t product_id) {
  hal::DeviceInfo d;
  d.backend = "sim";
  d.path = "script";
  const hal::DeviceQuirks* q = hal::find_quirks(vendor_id, product_id);
  d.name = q ? std::string(q->name) : "scripted device";
  d.manufacturer = "3Dconnexion";
  d.vendor_id = vendor_id;
  d.product_id = product_id;
  d.usage_page = 1;
  d.usage = 8;
  return d;
}

hal::NormalizerConfig scripted_normalizer() {
  hal::NormalizerConfig c;
  c.deadzone.fill(0.0f);
  c.curve = hal::CurveKind::kLinear;
  c.filter = false;
  return c;
}

SessionScript::SessionScript(hal::DeviceInfo device, hal::NormalizerConfig normalizer,
                             int report_hz, hal::PoseIntegratorConfig pose)
    : quirks_(hal::find_quirks(device.vendor_id, device.product_id)),
      normalizer_(normalizer),
      integrator_(pose),
      pose_config_(pose),
      period_ns_(1'000'000'000 / std::max(report_hz, 1)) {
  assert(quirks_ != nullptr && "scripted sessions emulate a device of the quirks table");
  session_.header.device = device;
  session_.header.normalizer_config = hal::to_text(normalizer);
  pipeline_ = fresh_pipeline();
}

std::unique_ptr<hal::MotionPipeline> SessionScript::fresh_pipeline() const {
  auto parser = hal::make_parser(session_.header.device);
  assert(parser.ok());
  return std::make_unique<hal::MotionPipeline>(std::move(parser).value(), normalizer_);
}

SessionScript::~SessionScript() = default;

const hal::ToolPose& SessionScript::pose() const {
  return integrator_.pose();
}

void SessionScript::command(const Command& c) {
  session_.records.push_back(SessionRecord::of(t_ns_, c));
  tick();
}

void SessionScript::volume(glm::ivec3 size, uint8_t fill) {
  Command c{CommandKind::kVolume};
  c.values[0] = static_cast<float>(size.x);
  c.values[1] = static_cast<float>(size.y);
  c.values[2] = static_cast<float>(size.z);
  c.values[3] = fill;
  command(c);
}

void SessionScript::tool(ToolShape shape, float a, float b) {
  Command c{CommandKind::kTool, static_cast<uint8_t>(shape)};
  c.values[0] = a;
  c.values[1] = b;
  command(c);
}

void SessionScript::mode(SculptModeId mode) {
  command({CommandKind::kMode, static_cast<uint8_t>(mode)});
}

void SessionScript::strength(float strength) {
  Command c{CommandKind::kStrength};
  c.values[0] = strength;
  command(c);
}

void SessionScript::spacing(float fraction) {
  Command c{CommandKind::kSpacing};
  c.values[0] = fraction;
  command(c);
}

void SessionScript::mirror(int axis, float at) {
  Command c{CommandKind::kMirror, axis < 0 ? kMirrorOff : static_cast<uint8_t>(axis)};
  c.values[0] = at;
  command(c);
}

void SessionScript::undo() {
  command({CommandKind::kUndo});
}
void SessionScript::redo() {
  command({CommandKind::kRedo});
}

void SessionScript::place(glm::vec3 p, glm::quat q) {
  Command c{CommandKind::kToolPose};
  c.values[0] = p.x;
  c.values[1] = p.y;
  c.values[2] = p.z;
  c.values[3] = q.w;
  c.values[4] = q.x;
  c.values[5] = q.y;
  c.values[6] = q.z;
  command(c);
  hal::ToolPose start;
  start.position = p;
  start.orientation = q;
  integrator_.reset(start);
}

void SessionScript::emit(std::span<const uint8_t> report) {
  const hal::RawEvent e = hal::RawEvent::report(t_ns_, report);
  session_.records.push_back(SessionRecord::of(e));
  scratch_.clear();
  pipeline_->feed(e, kDeviceId, scratch_);
  for (const hal::InputEvent& ie : scratch_)
    integrator_.update(ie);
}

void SessionScript::emit_motion(const std::array<float, 6>& axes) {
  // Invert the quirks' axis map: station axis i = sign[i] * raw[source[i]] / range.
  std::array<int16_t, 6> raw{};
  for (int i = 0; i < 6; ++i) {
    const float counts =
        std::clamp(axes[i], -1.0f, 1.0f) * quirks_->axis_range * quirks_->axis_sign[i];
    raw[quirks_->axis_source[i]] = static_cast<int16_t>(std::lround(counts));
  }
  auto put = [](uint8_t* at, int16_t v) {
    at[0] = static_cast<uint8_t>(v & 0xff);
    at[1] = static_cast<uint8_t>((v >> 8) & 0xff);
  };
  if (quirks_->layout == hal::MotionLayout::kCombined) {
    uint8_t r[13] = {1};
    for (int i = 0; i < 6; ++i)
      put(r + 1 + 2 * i, raw[i]);
    emit(r);
  } else {
    // Older devices send translation and rotation as two reports, 1 ms apart.
    uint8_t t[7] = {1};
    uint8_t r[7] = {2};
    for (int i = 0; i < 3; ++i) {
      put(t + 1 + 2 * i, raw[i]);
      put(r + 1 + 2 * i, raw[3 + i]);
    }
    emit(t);
    t_ns_ += 1'000'000;
    emit(r);
    t_ns_ -= 1'000'000;
  }
  last_axes_ = axes;
  tick();
}

void SessionScript::emit_buttons(uint32_t mask) {
  if (quirks_->buttons == hal::ButtonForm::kNumbered) {
    uint8_t r[5] = {0x1c};
    size_t n = 1;
    for (int b = 0; b < 32 && n < sizeof r; ++b)
      if (mask & (1u << b)) r[n++] = static_cast<uint8_t>(b + 1);
    emit(r);
  } else {
    uint8_t r[5] = {3, static_cast<uint8_t>(mask), static_cast<uint8_t>(mask >> 8),
                    static_cast<uint8_t>(mask >> 16), static_cast<uint8_t>(mask >> 24)};
    emit(r);
  }
  tick();
}

void SessionScript::press() {
  emit_buttons(1u);
}
void SessionScript::release() {
  emit_buttons(0u);
}

void SessionScript::follow(const Path& path, float seconds, const Turn& turn) {
  const int steps =
      std::max(1, static_cast<int>(std::lround(seconds * 1e9 / static_cast<double>(period_ns_))));
  const float dt = static_cast<float>(period_ns_) * 1e-9f;
  for (int k = 1; k <= steps; ++k) {
    const float s = static_cast<float>(k) / static_cast<float>(steps);
    const hal::ToolPose& now = integrator_.pose();
    // Motion over the next interval is the average of this report's and the
    // previous one's deflection (trapezoid): aim the average at the target,
    // and split the correction so the loop settles instead of ringing.
    std::array<float, 6> axes{};
    const glm::vec3 wanted = (path(s) - now.position) / (dt * pose_config_.max_speed);
    glm::vec3 twist(0.0f);
    if (turn) {
      glm::quat r = turn(s) * glm::inverse(now.orientation);
      if (r.w < 0) r = -r;
      const float angle = 2.0f * std::acos(std::clamp(r.w, -1.0f, 1.0f));
      const float sin_half = std::sqrt(std::max(0.0f, 1.0f - r.w * r.w));
      if (sin_half > 1e-6f)
        twist = glm::vec3(r.x, r.y, r.z) / sin_half * angle / (dt * pose_config_.max_angular_speed);
    }
    for (int i = 0; i < 3; ++i) {
      axes[i] = 1.5f * wanted[i] - 0.5f * last_axes_[i];
      axes[3 + i] = 1.5f * twist[i] - 0.5f * last_axes_[3 + i];
    }
    emit_motion(axes);
  }
}

void SessionScript::move_to(glm::vec3 target, float seconds) {
  follow(line_path(integrator_.pose().position, target), seconds);
}

void SessionScript::rest(float seconds) {
  emit_motion({});
  t_ns_ += static_cast<int64_t>(static_cast<double>(seconds) * 1e9);
}

void SessionScript::unplug_and_replug(float seconds) {
  const hal::RawEvent removed = hal::RawEvent::removed(t_ns_);
  session_.records.push_back(SessionRecord::of(removed));
  scratch_.clear();
  pipeline_->feed(removed, kDeviceId, scratch_);
  // Plugged back in, the device reports through a new pipeline (its integral
  // from zero) and the station's integrator starts a new stream, in replay
  // as live: the script steers from what they make of it.
  pipeline_ = fresh_pipeline();
  integrator_.start_stream(kDeviceId);
  t_ns_ += static_cast<int64_t>(static_cast<double>(seconds) * 1e9);
  last_axes_ = {};
}

Path line_path(glm::vec3 from, glm::vec3 to) {
  return [=](float s) { return from + (to - from) * s; };
}

Path arc_path(glm::vec3 centre, glm::vec3 u, glm::vec3 v, float radius, float a0, float a1) {
  return [=](float s) {
    const float a = a0 + (a1 - a0) * s;
    return centre + radius * (std::cos(a) * u + std::sin(a) * v);
  };
}

Path helix_path(glm::vec3 centre, glm::vec3 axis, float radius, float turns, float rise) {
  const glm::vec3 helper = std::abs(axis.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  const glm::vec3 u = glm::normalize(glm::cross(axis, helper));
  const glm::vec3 v = glm::cross(axis, u);
  return [=](float s) {
    const float a = 2.0f * kPi * turns * s;
    return centre + radius * (std::cos(a) * u + std::sin(a) * v) + axis * (rise * s);
  };
}

Path spiral_path(glm::vec3 centre, glm::vec3 u, glm::vec3 v, float r0, float r1, float turns) {
  return [=](float s) {
    const float a = 2.0f * kPi * turns * s;
    const float r = r0 + (r1 - r0) * s;
    return centre + r * (std::cos(a) * u + std::sin(a) * v);
  };
}

Path zigzag_path(glm::vec3 from, glm::vec3 direction, glm::vec3 across, float length,
                 float amplitude, int teeth) {
  return [=](float s) {
    const float phase = s * static_cast<float>(teeth) * 2.0f;  // two legs per tooth
    const float leg = phase - std::floor(phase);
    const float height = (static_cast<int>(std::floor(phase)) % 2 == 0) ? leg : 1.0f - leg;
    return from + direction * (length * s) + across * (amplitude * height);
  };
}

}  // namespace sculpt::sim
