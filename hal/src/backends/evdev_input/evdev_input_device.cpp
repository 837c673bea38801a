// EvdevInputDevice and the listing of 6-axis nodes. Sources: the kernel's
// Documentation/input/event-codes.rst (frames, SYN_DROPPED and the resync
// through EVIOCGABS/EVIOCGKEY, INPUT_PROP_ACCELEROMETER),
// drivers/hid/hid-input.c (a multi-axis controller's buttons become BTN_0..
// (BTN_MISC + n), a joystick's BTN_TRIGGER.., a gamepad's BTN_SOUTH..), and
// spacenavd's dev_usb_linux.c, which reads EV_REL and EV_ABS axes alike.

#include "backends/evdev_input/evdev_input_device.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "sculpt/hal/types/clock.h"

namespace sculpt::hal::evdev_input {
namespace {

using evdev_ff::evdev_bit;

constexpr const char* kAxisNames[6] = {"X", "Y", "Z", "RX", "RY", "RZ"};

// The key codes that are a 6-axis device's buttons: BTN_MISC.. up to the
// joystick range (hid-input numbers a multi-axis controller's buttons from
// BTN_0, and a device with more than 16 runs on into the mouse codes), and
// the BTN_TRIGGER_HAPPY block it uses past those.
bool is_button(uint16_t code) {
  return (code >= BTN_MISC && code < BTN_JOYSTICK) ||
         (code >= BTN_TRIGGER_HAPPY && code <= BTN_TRIGGER_HAPPY40);
}

// Six axes and a joystick's or gamepad's buttons are two sticks and two
// triggers (an Xbox pad has ABS_X..ABS_RZ), not a 6-DOF controller; the
// kernel's joydev and udev's input_id tell joysticks by these same codes.
bool has_stick_buttons(std::span<const uint8_t> keys) {
  for (uint16_t code = BTN_JOYSTICK; code < BTN_DIGI; ++code) {
    if (evdev_bit(keys, code)) return true;
  }
  return false;
}

template <size_t N>
std::array<uint8_t, N> bits_from_sysfs(const std::string& bitmap) {
  std::array<uint8_t, N> bits{};
  for (size_t i = 0; i < N * 8; ++i) {
    if (evdev_ff::sysfs_bitmap_bit(bitmap, i))
      bits[i / 8] = static_cast<uint8_t>(bits[i / 8] | (1u << (i % 8)));
  }
  return bits;
}

using EvBits = std::array<uint8_t, (EV_CNT + 7) / 8>;
using AbsBits = std::array<uint8_t, (ABS_CNT + 7) / 8>;
using RelBits = std::array<uint8_t, (REL_CNT + 7) / 8>;
using KeyBits = std::array<uint8_t, (KEY_CNT + 7) / 8>;
using PropBits = std::array<uint8_t, (INPUT_PROP_CNT + 7) / 8>;

// The layout sysfs describes, without the ranges (only the node has them).
Result<EvdevLayout> sysfs_layout(const evdev_ff::EvdevSysfs& s, const EvdevInputOptions& options) {
  const auto ev = bits_from_sysfs<EvBits{}.size()>(s.ev_bitmap);
  const auto abs = bits_from_sysfs<AbsBits{}.size()>(s.abs_bitmap);
  const auto rel = bits_from_sysfs<RelBits{}.size()>(s.rel_bitmap);
  const auto keys = bits_from_sysfs<KeyBits{}.size()>(s.key_bitmap);
  const auto props = bits_from_sysfs<PropBits{}.size()>(s.properties_bitmap);
  return evdev_6axis_layout(ev, abs, rel, keys, props, options);
}

struct Capabilities {
  EvBits ev{};
  AbsBits abs{};
  RelBits rel{};
  KeyBits keys{};
};

// 0 or -errno.
int read_capabilities(evdev_ff::EvdevIo& io, Capabilities& c) {
  if (const int r = io.get_bits(0, c.ev); r < 0) return r;
  if (evdev_bit(c.ev, EV_ABS)) {
    if (const int r = io.get_bits(EV_ABS, c.abs); r < 0) return r;
  }
  if (evdev_bit(c.ev, EV_REL)) {
    if (const int r = io.get_bits(EV_REL, c.rel); r < 0) return r;
  }
  if (evdev_bit(c.ev, EV_KEY)) {
    if (const int r = io.get_bits(EV_KEY, c.keys); r < 0) return r;
  }
  return 0;
}

PropBits sysfs_props(const std::optional<evdev_ff::EvdevSysfs>& s) {
  return s ? bits_from_sysfs<PropBits{}.size()>(s->properties_bitmap) : PropBits{};
}

}  // namespace

Result<EvdevLayout> evdev_6axis_layout(std::span<const uint8_t> ev, std::span<const uint8_t> abs,
                                       std::span<const uint8_t> rel, std::span<const uint8_t> keys,
                                       std::span<const uint8_t> props,
                                       const EvdevInputOptions& options) {
  EvdevLayout layout;
  const bool has_abs = evdev_bit(ev, EV_ABS);
  const bool has_rel = evdev_bit(ev, EV_REL);
  for (uint16_t code = 0; code < 6; ++code) {
    EvdevAxisRange& a = layout.axes[code];
    if (has_abs && evdev_bit(abs, code)) {
      a.kind = EvdevAxisKind::kAbsolute;
    } else if (has_rel && evdev_bit(rel, code)) {
      a.kind = EvdevAxisKind::kRelative;
      a.minimum = 0;
      a.maximum = std::max(options.relative_full_scale, 1);
    } else {
      return Error(std::string("no axis ") + kAxisNames[code] + " (not a 6-axis device)");
    }
  }
  // Phones' and pads' motion sensors have the six axes too.
  if (evdev_bit(props, INPUT_PROP_ACCELEROMETER))
    return Error("a motion sensor (INPUT_PROP_ACCELEROMETER), not a 6-axis controller");
  if (evdev_bit(ev, EV_KEY) && has_stick_buttons(keys))
    return Error("a joystick or gamepad (its six axes are sticks and triggers)");
  if (evdev_bit(ev, EV_KEY)) {
    for (uint16_t code = 0; code < KEY_CNT; ++code) {
      if (layout.button_codes.size() == EvdevLayout::kMaxButtons) break;
      if (is_button(code) && evdev_bit(keys, code)) layout.button_codes.push_back(code);
    }
  }
  return layout;
}

std::vector<DeviceInfo> list_evdev_6axis_devices(evdev_ff::EvdevIo& io,
                                                 const EvdevInputOptions& options) {
  std::vector<DeviceInfo> found;
  for (const std::string& node : io.list_event_nodes()) {
    const std::optional<evdev_ff::EvdevSysfs> sys = io.sysfs(node);
    const bool sysfs_knows = sys && !sys->ev_bitmap.empty();
    // Sysfs rules most nodes out (keyboards, mice) without opening them.
    if (sysfs_knows && !sysfs_layout(*sys, options)) continue;
    DeviceInfo info;
    info.backend = "evdev";
    info.path = node;
    if (sys) {
      info.name = sys->name;
      info.vendor_id = sys->vendor_id;
      info.product_id = sys->product_id;
      info.usb_location = sys->usb_location;
      info.serial = sys->uniq;
    }
    const int r = io.open(node);
    if (r == -EACCES || r == -EPERM) {
      // Without sysfs nothing says this node has six axes: leave it out
      // rather than list every keyboard the user may not open.
      if (!sysfs_knows) continue;
      info.accessible = false;
      found.push_back(std::move(info));
      continue;
    }
    if (r < 0) continue;  // gone since the directory was read
    Capabilities c;
    input_id id{};
    std::string name;
    const bool ok = read_capabilities(io, c) == 0 &&
                    evdev_6axis_layout(c.ev, c.abs, c.rel, c.keys, sysfs_props(sys), options) &&
                    io.get_id(id) == 0 && io.get_name(name) == 0;
    io.close();
    if (!ok) continue;
    info.name = name;
    info.vendor_id = id.vendor;
    info.product_id = id.product;
    found.push_back(std::move(info));
  }
  return found;
}

EvdevInputDevice::EvdevInputDevice(std::unique_ptr<evdev_ff::EvdevIo> io, EvdevInputOptions options)
    : io_(std::move(io)), options_(std::move(options)) {}

EvdevInputDevice::~EvdevInputDevice() {
  io_->close();
}

Result<std::unique_ptr<EvdevInputDevice>> EvdevInputDevice::open(
    std::unique_ptr<evdev_ff::EvdevIo> io, const std::string& path, EvdevInputOptions options) {
  if (const int r = io->open(path); r < 0) return Error(evdev_ff::evdev_open_error(path, r));
  std::unique_ptr<EvdevInputDevice> d(new EvdevInputDevice(std::move(io), std::move(options)));
  evdev_ff::EvdevIo& io_ref = *d->io_;
  auto fail = [&](const std::string& step, int r) {
    return Error(path + ": " + step + ": " + std::strerror(-r));
  };
  const std::optional<evdev_ff::EvdevSysfs> sys = io_ref.sysfs(path);
  Capabilities c;
  if (const int r = read_capabilities(io_ref, c); r < 0) return fail("reading its capabilities", r);
  auto layout = evdev_6axis_layout(c.ev, c.abs, c.rel, c.keys, sysfs_props(sys), d->options_);
  if (!layout) return layout.error().in(path);
  d->layout_ = std::move(layout).value();
  for (uint16_t code = 0; code < 6; ++code) {
    EvdevAxisRange& a = d->layout_.axes[code];
    if (a.kind != EvdevAxisKind::kAbsolute) continue;
    input_absinfo range{};
    if (const int r = io_ref.get_abs(code, range); r < 0) return fail("reading an axis range", r);
    if (range.maximum <= range.minimum) {
      return Error(path + ": axis " + kAxisNames[code] + " has an empty range (" +
                   std::to_string(range.minimum) + ".." + std::to_string(range.maximum) + ")");
    }
    a.minimum = range.minimum;
    a.maximum = range.maximum;
  }
  input_id id{};
  if (const int r = io_ref.get_id(id); r < 0) return fail("reading its vendor and product", r);
  DeviceInfo& info = d->info_;
  info.backend = "evdev";
  info.path = path;
  info.vendor_id = id.vendor;
  info.product_id = id.product;
  if (const int r = io_ref.get_name(info.name); r < 0) return fail("reading its name", r);
  if (sys) {
    info.usb_location = sys->usb_location;
    info.serial = sys->uniq;
  }
  info.report_descriptor = encode_evdev_layout(d->layout_);
  d->now_ns_ = monotonic_ns();
  if (!d->queue_state_frame()) return Error(path + ": reading its axes and buttons failed");
  return d;
}

void EvdevInputDevice::log(const std::string& line) {
  const std::string full = "evdev: " + info_.path + ": " + line;
  if (options_.log) {
    options_.log(full);
  } else {
    std::fprintf(stderr, "%s\n", full.c_str());
  }
}

void EvdevInputDevice::queue(const EvdevRecord& r) {
  filling_.push_back(r);
  if (filling_.size() == kEvdevRecordsPerReport) flush();
}

void EvdevInputDevice::flush() {
  if (filling_.empty()) return;
  std::array<uint8_t, kEvdevRecordsPerReport * kEvdevRecordBytes> bytes{};
  for (size_t i = 0; i < filling_.size(); ++i)
    encode_evdev_record(filling_[i], bytes.data() + i * kEvdevRecordBytes);
  ready_.push_back(
      RawEvent::report(now_ns_, std::span(bytes.data(), filling_.size() * kEvdevRecordBytes)));
  filling_.clear();
}

bool EvdevInputDevice::queue_state_frame() {
  for (uint16_t code = 0; code < 6; ++code) {
    if (layout_.axes[code].kind != EvdevAxisKind::kAbsolute) continue;
    input_absinfo now{};
    if (io_->get_abs(code, now) < 0) return false;
    queue({EV_ABS, code, now.value});
  }
  if (!layout_.button_codes.empty()) {
    KeyBits held{};
    if (io_->get_key_state(held) < 0) return false;
    for (uint16_t code : layout_.button_codes)
      queue({EV_KEY, code, evdev_bit(held, code) ? 1 : 0});
  }
  queue({EV_SYN, SYN_REPORT, 0});
  flush();
  return true;
}

void EvdevInputDevice::end(const std::string& why) {
  if (removed_) return;
  removed_ = true;
  flush();
  log(why);
}

void EvdevInputDevice::take(const input_event& ev) {
  ++counters_.events;
  if (ev.type == EV_SYN) {
    if (ev.code == SYN_DROPPED) {
      ++counters_.overruns;
      dropping_ = true;
      queue({EV_SYN, SYN_DROPPED, 0});
      return;
    }
    if (ev.code != SYN_REPORT) return;
    ++counters_.frames;
    queue({EV_SYN, SYN_REPORT, 0});
    flush();
    last_frame_ns_ = now_ns_;
    if (dropping_) {
      // The frame the overrun cut is dropped by the parser; the state read
      // now replaces it (a relative axis has no state: it reads 0).
      dropping_ = false;
      relative_moving_ = false;
      frame_moved_relative_ = false;
      if (!queue_state_frame()) end("gone while reading its state after an overrun");
      return;
    }
    relative_moving_ = frame_moved_relative_;
    frame_moved_relative_ = false;
    return;
  }
  if (dropping_) return;  // dropped by the parser anyway: not worth recording
  if ((ev.type == EV_ABS || ev.type == EV_REL) && ev.code < 6) {
    const EvdevAxisKind want =
        ev.type == EV_ABS ? EvdevAxisKind::kAbsolute : EvdevAxisKind::kRelative;
    if (layout_.axes[ev.code].kind != want) return;
    if (ev.type == EV_REL && ev.value != 0) frame_moved_relative_ = true;
    queue({ev.type, ev.code, ev.value});
    return;
  }
  if (ev.type == EV_KEY && std::find(layout_.button_codes.begin(), layout_.button_codes.end(),
                                     ev.code) != layout_.button_codes.end()) {
    queue({EV_KEY, ev.code, ev.value});
  }
}

ReadResult EvdevInputDevice::read(RawEvent& out, int timeout_ms) {
  if (!ready_.empty()) {
    out = ready_.front();
    ready_.pop_front();
    ++counters_.reports;
    return ReadResult::kEvent;
  }
  if (removed_) {
    out = RawEvent::removed(monotonic_ns());
    return ReadResult::kRemoved;
  }
  const int64_t release_ns = int64_t{std::max(options_.rel_release_ms, 0)} * 1'000'000;
  int wait = std::max(timeout_ms, 0);
  if (relative_moving_) {
    const int64_t left_ns = last_frame_ns_ + release_ns - monotonic_ns();
    wait = static_cast<int>(std::clamp<int64_t>((left_ns + 999'999) / 1'000'000, 0, wait));
  }
  const int r = io_->poll_readable(wait);
  now_ns_ = monotonic_ns();
  if (r < 0) {
    end(r == -ENODEV ? std::string("gone (unplugged)")
                     : std::string("poll failed: ") + std::strerror(-r) + "; closing it");
  } else if (r == 0) {
    if (relative_moving_ && now_ns_ - last_frame_ns_ >= release_ns) {
      // See the header: the released cap's zeros never arrive.
      relative_moving_ = false;
      ++counters_.releases;
      last_frame_ns_ = now_ns_;
      queue({EV_SYN, SYN_REPORT, 0});
      flush();
    }
  } else {
    // Drain without waiting; bounded, so a flood cannot hold the reader.
    std::array<uint8_t, 64 * sizeof(input_event)> buf{};
    for (int i = 0; i < 8 && !removed_; ++i) {
      const long n = io_->read_bytes(buf);
      if (n == -EAGAIN || n == 0) break;
      if (n < 0) {
        end(n == -ENODEV ? std::string("gone (unplugged)")
                         : std::string("read failed: ") + std::strerror(static_cast<int>(-n)) +
                               "; closing it");
        break;
      }
      const size_t bytes = std::min(static_cast<size_t>(n), buf.size());
      const size_t whole = bytes / sizeof(input_event);
      for (size_t k = 0; k < whole && !removed_; ++k) {
        input_event ev;
        std::memcpy(&ev, buf.data() + k * sizeof(input_event), sizeof ev);
        take(ev);
      }
      if (const size_t stray = bytes - whole * sizeof(input_event); stray > 0) {
        // evdev_read() hands out whole records only: something else is
        // behind this node.
        counters_.stray_bytes += static_cast<int64_t>(stray);
        if (!stray_logged_) {
          stray_logged_ = true;
          log("read " + std::to_string(stray) + " bytes that make no whole input_event (" +
              std::to_string(sizeof(input_event)) + " bytes); dropped (further ones counted only)");
        }
      }
      if (bytes < buf.size()) break;
    }
    // Records after the last SYN_REPORT wait for the rest of their frame.
  }
  if (!ready_.empty() || removed_) return read(out, 0);
  return ReadResult::kTimeout;
}

}  // namespace sculpt::hal::evdev_input
