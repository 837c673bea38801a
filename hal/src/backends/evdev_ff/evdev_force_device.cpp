// EvdevForceDevice: the effect's life and the input frames. Sources: the
// kernel's Documentation/input/ff.rst (upload, update in place, play, gain,
// removal), Documentation/input/event-codes.rst (SYN_REPORT frames,
// SYN_DROPPED) and the comments of <linux/input.h>.

#include "evdev_force_device.h"

#include <algorithm>
#include <cassert>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <span>
#include <utility>

namespace sculpt::hal::evdev_ff {
namespace {

constexpr std::array<uint16_t, 3> kAxisCodes = {ABS_X, ABS_Y, ABS_Z};

// The button codes a stick or pad uses, in the order their bits are given:
// BTN_JOYSTICK (BTN_TRIGGER) .. BTN_DIGI-1 covers the joystick and gamepad
// ranges (BTN_SOUTH = 0x130), BTN_TRIGGER_HAPPY* the extra buttons of wheels
// and big sticks.
bool is_stick_button(uint16_t code) {
  return (code >= BTN_JOYSTICK && code < BTN_DIGI) ||
         (code >= BTN_TRIGGER_HAPPY && code <= BTN_TRIGGER_HAPPY40);
}

std::string ff_features(std::span<const uint8_t> ff) {
  static constexpr std::pair<uint16_t, const char*> kNames[] = {
      {FF_RUMBLE, "rumble"},   {FF_PERIODIC, "periodic"}, {FF_CONSTANT, "constant"},
      {FF_SPRING, "spring"},   {FF_FRICTION, "friction"}, {FF_DAMPER, "damper"},
      {FF_INERTIA, "inertia"}, {FF_RAMP, "ramp"},
  };
  std::string s;
  for (const auto& [code, name] : kNames) {
    if (!evdev_bit(ff, code)) continue;
    if (!s.empty()) s += ", ";
    s += name;
  }
  return s.empty() ? std::string("no effects") : s;
}

std::string errno_text(long minus_errno) {
  return std::strerror(static_cast<int>(-minus_errno));
}

}  // namespace

EvdevForceDevice::EvdevForceDevice(std::unique_ptr<EvdevIo> io, const EvdevForceOptions& options)
    : io_(std::move(io)), options_(options) {}

Result<std::unique_ptr<EvdevForceDevice>> EvdevForceDevice::open(std::unique_ptr<EvdevIo> io,
                                                                 const std::string& path,
                                                                 const EvdevForceOptions& options) {
  assert(io != nullptr);
  if (!(std::isfinite(options.full_scale_n) && options.full_scale_n > 0.0f))
    return Error(path + ": full-scale force must be a positive number of newtons");
  if (!(std::isfinite(options.workspace_half_range_mm) && options.workspace_half_range_mm > 0.0f))
    return Error(path + ": workspace half-range must be a positive number of millimetres");
  if (const int r = io->open(path); r < 0) return Error(evdev_open_error(path, r));
  // From here the device owns the io: its destructor closes the node and
  // removes an effect uploaded before a later step failed.
  std::unique_ptr<EvdevForceDevice> d(new EvdevForceDevice(std::move(io), options));
  EvdevIo& io_ref = *d->io_;
  auto fail = [&](const std::string& step, long r) {
    return Error(path + ": " + step + ": " + errno_text(r));
  };

  // ff.rst "Querying device capabilities": EVIOCGBIT(EV_FF) lists the
  // effects; a device without EV_FF has none.
  std::array<uint8_t, (EV_CNT + 7) / 8> ev{};
  std::array<uint8_t, (FF_CNT + 7) / 8> ff{};
  if (const int r = io_ref.get_bits(0, ev); r < 0) return fail("reading its event types", r);
  if (evdev_bit(ev, EV_FF)) {
    if (const int r = io_ref.get_bits(EV_FF, ff); r < 0)
      return fail("reading its force-feedback features", r);
  }
  if (!evdev_bit(ff, FF_CONSTANT)) {
    return Error(path + ": cannot play a constant force (no FF_CONSTANT; it offers " +
                 ff_features(ff) + "), so it cannot be a force device");
  }

  input_id id{};
  if (const int r = io_ref.get_id(id); r < 0) return fail("reading its vendor and product", r);
  DeviceInfo& info = d->info_;
  info.backend = "evdev-ff";
  info.path = path;
  info.vendor_id = id.vendor;
  info.product_id = id.product;
  if (const int r = io_ref.get_name(info.name); r < 0) return fail("reading its name", r);
  if (const auto sys = io_ref.sysfs(path)) info.usb_location = sys->usb_location;

  // The limits table knows a few devices by vendor:product; any other stick
  // gets limits built from the options (kEffectBased: the table's rows are
  // for devices whose newtons are measured, a stick's are what the user
  // says full scale is).
  if (const ForceLimits* known = find_force_limits(id.vendor, id.product)) {
    d->limits_ = *known;
  } else {
    ForceLimits& l = d->limits_;
    l.vendor_id = id.vendor;
    l.product_id = id.product;
    l.name = d->info_.name;  // the device owns info_, so the view stays valid
    l.capability = ForceCapability::kEffectBased;
    l.max_force_n = options.full_scale_n;
    l.max_stiffness_n_per_mm = options.max_stiffness_n_per_mm;
    l.max_damping_ns_per_m = options.max_damping_ns_per_m;
    // The stick's normalised range [-1, 1] is reported as
    // ±workspace_half_range_mm, so that is its reach in mm.
    l.workspace_radius_mm = options.workspace_half_range_mm;
  }

  std::array<uint8_t, (ABS_CNT + 7) / 8> abs{};
  if (evdev_bit(ev, EV_ABS)) {
    if (const int r = io_ref.get_bits(EV_ABS, abs); r < 0) return fail("reading its axes", r);
  }
  for (size_t i = 0; i < kAxes; ++i) {
    if (!evdev_bit(abs, kAxisCodes[i])) continue;
    Axis& a = d->axes_[i];
    if (const int r = io_ref.get_abs(kAxisCodes[i], a.range); r < 0)
      return fail("reading an axis range", r);
    a.present = a.range.maximum > a.range.minimum;
    d->state_.axis[i] = a.range.value;
  }
  std::array<uint8_t, (KEY_CNT + 7) / 8> keys{};
  if (evdev_bit(ev, EV_KEY)) {
    if (const int r = io_ref.get_bits(EV_KEY, keys); r < 0) return fail("reading its buttons", r);
    for (uint16_t code = 0; code < KEY_CNT && d->button_codes_.size() < kMaxButtons; ++code) {
      if (is_stick_button(code) && evdev_bit(keys, code)) d->button_codes_.push_back(code);
    }
    if (const int r = d->resync(); r < 0) return fail("reading its buttons", r);
  }
  d->pending_ = d->state_;

  // ff.rst "Setting the gain": a write of EV_FF/FF_GAIN, 0..0xffff; the
  // input core ignores it on a device without FF_GAIN, so it is sent only
  // where it means something.
  if (evdev_bit(ff, FF_GAIN)) {
    if (const int r = d->send_event(EV_FF, FF_GAIN, options.gain); r < 0)
      return fail("setting the gain", r);
  }
  if (options.autocenter_off && evdev_bit(ff, FF_AUTOCENTER)) {
    if (const int r = d->send_event(EV_FF, FF_AUTOCENTER, 0); r < 0)
      return fail("turning the centring spring off", r);
  }

  // ff.rst "Uploading effects": id -1 asks for a new effect; the kernel
  // writes its id back. Level 0, so nothing moves until the loop writes.
  if (const int r = d->upload(ConstantEffectCommand{}); r < 0)
    return fail("uploading the constant-force effect", r);
  // ff.rst "Controlling the playback": value = how many times to play; with
  // replay.length 0 once lasts until it is stopped.
  if (const int r = d->send_event(EV_FF, static_cast<uint16_t>(d->effect_id_), 1); r < 0)
    return fail("starting the effect", r);
  d->playing_ = true;
  return d;
}

EvdevForceDevice::~EvdevForceDevice() {
  // ff.rst: EVIOCRMFF also stops the effect. Effects die with the file
  // descriptor anyway; removing it first frees the slot at once.
  if (!removed_ && effect_id_ >= 0) (void)io_->remove_effect(effect_id_);
  io_->close();
}

ForceIo EvdevForceDevice::failure(long minus_errno) {
  if (minus_errno == -ENODEV) {
    removed_ = true;
    return ForceIo::kRemoved;
  }
  ++counters_.io_errors;
  return ForceIo::kFault;
}

int EvdevForceDevice::send_event(uint16_t type, uint16_t code, int32_t value) {
  // The kernel ignores the time of an event written to it.
  input_event ev{};
  ev.type = type;
  ev.code = code;
  ev.value = value;
  const long n = io_->write_bytes(std::span(reinterpret_cast<const uint8_t*>(&ev), sizeof ev));
  if (n < 0) return static_cast<int>(n);
  return n == static_cast<long>(sizeof ev) ? 0 : -EIO;
}

int EvdevForceDevice::upload(const ConstantEffectCommand& command) {
  ff_effect e{};
  e.type = FF_CONSTANT;
  e.id = effect_id_;
  e.direction = command.direction;
  // replay.length 0 = play until stopped: ff-memless only sets a stop time
  // when the length is non-zero, and hid-pidff (HID PID sticks and wheels)
  // turns 0 into the PID's infinite duration. The longest finite length is
  // 32767 ms (<linux/input.h>: "values above 32767 ms should not be used"),
  // far shorter than a session; effect_length_ms is there for a driver
  // that takes 0 literally (hid-pidff before that conversion was added),
  // and then write() restarts the effect at every update.
  e.replay.length = options_.effect_length_ms;
  e.replay.delay = 0;
  e.u.constant.level = command.level;
  const int r = io_->upload_effect(e);
  if (r < 0) return r;
  effect_id_ = e.id;
  sent_ = command;
  return 0;
}

int EvdevForceDevice::button_bit(uint16_t code) const {
  const auto it = std::find(button_codes_.begin(), button_codes_.end(), code);
  return it == button_codes_.end() ? -1 : static_cast<int>(it - button_codes_.begin());
}

int EvdevForceDevice::resync() {
  for (size_t i = 0; i < kAxes; ++i) {
    if (!axes_[i].present) continue;
    input_absinfo now{};
    if (const int r = io_->get_abs(kAxisCodes[i], now); r < 0) return r;
    state_.axis[i] = now.value;
  }
  if (!button_codes_.empty()) {
    std::array<uint8_t, (KEY_CNT + 7) / 8> held{};
    if (const int r = io_->get_key_state(held); r < 0) return r;
    state_.buttons = 0;
    for (size_t i = 0; i < button_codes_.size(); ++i) {
      if (evdev_bit(held, button_codes_[i])) state_.buttons |= 1u << i;
    }
  }
  return 0;
}

void EvdevForceDevice::take(const input_event& ev) {
  ++counters_.events;
  if (ev.type == EV_SYN && ev.code == SYN_DROPPED) {
    // event-codes.rst: the queue overran; ignore everything up to and
    // including the next SYN_REPORT, then ask the device for its state.
    ++counters_.overruns;
    dropping_ = true;
    return;
  }
  if (ev.type == EV_SYN && ev.code == SYN_REPORT) {
    if (dropping_) {
      dropping_ = false;
      // A failed re-read keeps the last state; the next overrun tries again.
      if (resync() == -ENODEV) removed_ = true;
    } else {
      state_ = pending_;
    }
    pending_ = state_;
    ++counters_.frames;
    return;
  }
  if (dropping_) return;
  if (ev.type == EV_ABS) {
    for (size_t i = 0; i < kAxes; ++i) {
      if (axes_[i].present && ev.code == kAxisCodes[i]) pending_.axis[i] = ev.value;
    }
  } else if (ev.type == EV_KEY) {
    const int bit = button_bit(ev.code);
    if (bit < 0) return;
    // value 0 = released, 1 = pressed, 2 = autorepeat (still held).
    if (ev.value != 0) {
      pending_.buttons |= 1u << bit;
    } else {
      pending_.buttons &= ~(1u << bit);
    }
  }
}

ForceIo EvdevForceDevice::read(ForceDeviceState& out) {
  if (removed_) return ForceIo::kRemoved;
  ForceIo result = ForceIo::kOk;
  if (options_.read_wait_ms > 0) {
    const int r = io_->poll_readable(options_.read_wait_ms);
    if (r < 0) result = failure(r);
  }
  // Drain what is pending without waiting; a bounded number of reads, so a
  // flood of events cannot hold the tick.
  constexpr int kMaxReads = 8;
  for (int i = 0; i < kMaxReads && result == ForceIo::kOk; ++i) {
    const long n = io_->read_bytes(read_buf_);
    if (n == -EAGAIN || n == 0) break;
    if (n < 0) {
      result = failure(n);
      break;
    }
    const size_t bytes = std::min(static_cast<size_t>(n), read_buf_.size());
    const size_t whole = bytes / sizeof(input_event);
    // evdev hands out whole records only (evdev_read); a remainder means
    // something else is behind the descriptor: drop it, counted.
    counters_.stray_bytes += static_cast<int64_t>(bytes - whole * sizeof(input_event));
    for (size_t k = 0; k < whole && !removed_; ++k) {
      input_event ev;
      std::memcpy(&ev, read_buf_.data() + k * sizeof(input_event), sizeof ev);
      take(ev);
    }
    if (removed_) result = ForceIo::kRemoved;
    if (bytes < read_buf_.size()) break;
  }
  const float half = options_.workspace_half_range_mm;
  auto axis = [&](size_t i) {
    return axes_[i].present ? normalised_axis(state_.axis[i], axes_[i].range) : 0.0f;
  };
  out.position_mm = glm::vec3(axis(0) * half, -axis(1) * half, axis(2) * half);
  out.buttons = state_.buttons;
  out.homed = true;
  return result;
}

ForceIo EvdevForceDevice::write(glm::vec3 force_n) {
  if (removed_) return ForceIo::kRemoved;
  const bool finite =
      std::isfinite(force_n.x) && std::isfinite(force_n.y) && std::isfinite(force_n.z);
  const ConstantEffectCommand next = constant_effect_for_force(
      finite ? force_n : glm::vec3(0.0f), limits_.max_force_n, sent_.direction);
  if (!(next == sent_)) {
    // ff.rst "Dynamic update of an effect": the same upload with the id the
    // kernel gave; the effect goes on playing (a driver that cannot change
    // a playing effect's direction restarts it itself).
    if (const int r = upload(next); r < 0) return failure(r);
    ++counters_.effect_updates;
    if (playing_ && options_.effect_length_ms != 0 && next.level != 0) {
      // A finite effect would run out during a long contact: restart it.
      if (const int r = send_event(EV_FF, static_cast<uint16_t>(effect_id_), 1); r < 0)
        return failure(r);
    }
  }
  if (!playing_ && sent_.level != 0) {
    if (const int r = send_event(EV_FF, static_cast<uint16_t>(effect_id_), 1); r < 0)
      return failure(r);
    playing_ = true;
  }
  return finite ? ForceIo::kOk : ForceIo::kFault;
}

void EvdevForceDevice::zero() noexcept {
  if (removed_ || effect_id_ < 0) return;
  // Level 0 first, so that a driver that does not stop at once (or a stop
  // that is lost) leaves no force; then stop (ff.rst: value 0 stops).
  if (sent_.level != 0) {
    ConstantEffectCommand none = sent_;
    none.level = 0;
    if (const int r = upload(none); r < 0) {
      (void)failure(r);
      if (removed_) return;
    }
  }
  if (playing_) {
    if (const int r = send_event(EV_FF, static_cast<uint16_t>(effect_id_), 0); r < 0) {
      (void)failure(r);
      return;
    }
    playing_ = false;
  }
}

}  // namespace sculpt::hal::evdev_ff
