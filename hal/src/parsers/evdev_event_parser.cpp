// The evdev record and layout forms, and frames to motion and buttons.
// Sources: the kernel's Documentation/input/event-codes.rst (EV_SYN frames,
// SYN_DROPPED, EV_REL and EV_ABS) and drivers/input/input.c
// (input_handle_event(): a relative event of value 0 is never passed on, and
// an absolute one only when its value changed), which is why an absent
// relative axis reads 0 and an absent absolute axis keeps its value.

#include "sculpt/hal/parsers/evdev_event_parser.h"

#include <linux/input.h>

#include <algorithm>

namespace sculpt::hal {
namespace {

constexpr uint8_t kMagic[4] = {'E', 'V', 'D', '1'};
constexpr size_t kAxisBytes = 9;

void put32(std::vector<uint8_t>& out, uint32_t v) {
  for (int i = 0; i < 4; ++i)
    out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}

uint32_t get32(const uint8_t* in) {
  return static_cast<uint32_t>(in[0]) | static_cast<uint32_t>(in[1]) << 8 |
         static_cast<uint32_t>(in[2]) << 16 | static_cast<uint32_t>(in[3]) << 24;
}

uint16_t get16(const uint8_t* in) {
  return static_cast<uint16_t>(in[0] | in[1] << 8);
}

bool valid(const EvdevAxisRange& a) {
  if (a.kind == EvdevAxisKind::kAbsolute) return a.maximum > a.minimum;
  if (a.kind == EvdevAxisKind::kRelative) return a.maximum > 0;
  return false;
}

// [-1, 1] from counts; absolute around the middle of the range.
float normalised(int32_t value, const EvdevAxisRange& a) {
  double v;
  if (a.kind == EvdevAxisKind::kAbsolute) {
    const double mid = (static_cast<double>(a.minimum) + a.maximum) / 2.0;
    const double half = (static_cast<double>(a.maximum) - a.minimum) / 2.0;
    v = (value - mid) / half;
  } else {
    v = static_cast<double>(value) / a.maximum;
  }
  return static_cast<float>(std::clamp(v, -1.0, 1.0));
}

}  // namespace

std::string_view describe(EvdevLayoutError error) {
  switch (error) {
    case EvdevLayoutError::kNone:
      return "a valid evdev layout";
    case EvdevLayoutError::kBadMagic:
      return "not an evdev layout (no EVD1 magic)";
    case EvdevLayoutError::kShort:
      return "evdev layout cut short";
    case EvdevLayoutError::kBadAxis:
      return "evdev layout has an axis of unknown kind or empty range";
    case EvdevLayoutError::kTooManyButtons:
      return "evdev layout has more than 32 buttons";
    case EvdevLayoutError::kLong:
      return "evdev layout followed by stray bytes";
  }
  return "unknown evdev layout error";
}

std::vector<uint8_t> encode_evdev_layout(const EvdevLayout& layout) {
  std::vector<uint8_t> out(std::begin(kMagic), std::end(kMagic));
  for (const EvdevAxisRange& a : layout.axes) {
    out.push_back(static_cast<uint8_t>(a.kind));
    put32(out, static_cast<uint32_t>(a.minimum));
    put32(out, static_cast<uint32_t>(a.maximum));
  }
  const size_t n = std::min(layout.button_codes.size(), EvdevLayout::kMaxButtons);
  out.push_back(static_cast<uint8_t>(n));
  for (size_t i = 0; i < n; ++i) {
    out.push_back(static_cast<uint8_t>(layout.button_codes[i]));
    out.push_back(static_cast<uint8_t>(layout.button_codes[i] >> 8));
  }
  return out;
}

EvdevLayoutError decode_evdev_layout(std::span<const uint8_t> bytes, EvdevLayout& out) {
  if (bytes.size() < sizeof kMagic ||
      !std::equal(std::begin(kMagic), std::end(kMagic), bytes.begin()))
    return EvdevLayoutError::kBadMagic;
  size_t at = sizeof kMagic;
  EvdevLayout l;
  for (EvdevAxisRange& a : l.axes) {
    if (bytes.size() - at < kAxisBytes) return EvdevLayoutError::kShort;
    a.kind = static_cast<EvdevAxisKind>(bytes[at]);
    a.minimum = static_cast<int32_t>(get32(&bytes[at + 1]));
    a.maximum = static_cast<int32_t>(get32(&bytes[at + 5]));
    if (!valid(a)) return EvdevLayoutError::kBadAxis;
    at += kAxisBytes;
  }
  if (at == bytes.size()) return EvdevLayoutError::kShort;
  const size_t n = bytes[at++];
  if (n > EvdevLayout::kMaxButtons) return EvdevLayoutError::kTooManyButtons;
  if (bytes.size() - at < 2 * n) return EvdevLayoutError::kShort;
  for (size_t i = 0; i < n; ++i, at += 2)
    l.button_codes.push_back(get16(&bytes[at]));
  if (at != bytes.size()) return EvdevLayoutError::kLong;
  out = std::move(l);
  return EvdevLayoutError::kNone;
}

void encode_evdev_record(const EvdevRecord& record, uint8_t* out) {
  out[0] = static_cast<uint8_t>(record.type);
  out[1] = static_cast<uint8_t>(record.type >> 8);
  out[2] = static_cast<uint8_t>(record.code);
  out[3] = static_cast<uint8_t>(record.code >> 8);
  const auto v = static_cast<uint32_t>(record.value);
  for (int i = 0; i < 4; ++i)
    out[4 + i] = static_cast<uint8_t>(v >> (8 * i));
}

EvdevRecord decode_evdev_record(const uint8_t* in) {
  EvdevRecord r;
  r.type = get16(in);
  r.code = get16(in + 2);
  r.value = static_cast<int32_t>(get32(in + 4));
  return r;
}

EvdevEventParser::EvdevEventParser(EvdevLayout layout, const DeviceQuirks* quirks)
    : layout_(std::move(layout)), mapping_(quirks ? *quirks : DeviceQuirks{}) {
  if (layout_.button_codes.size() > EvdevLayout::kMaxButtons)
    layout_.button_codes.resize(EvdevLayout::kMaxButtons);
  for (size_t i = 0; i < 6; ++i) {
    const EvdevAxisRange& a = layout_.axes[i];
    has_relative_ = has_relative_ || a.kind == EvdevAxisKind::kRelative;
    // Rest at the middle of an absolute range until the device says more.
    if (a.kind == EvdevAxisKind::kAbsolute)
      value_[i] = static_cast<int32_t>((static_cast<int64_t>(a.minimum) + a.maximum) / 2);
  }
  pending_ = value_;
}

int EvdevEventParser::button_index(uint16_t code) const {
  const auto it = std::find(layout_.button_codes.begin(), layout_.button_codes.end(), code);
  return it == layout_.button_codes.end() ? -1
                                          : static_cast<int>(it - layout_.button_codes.begin());
}

void EvdevEventParser::parse(const RawEvent& event, std::vector<InputEvent>& out) {
  ++counters_.reports;
  if (event.kind != RawEventKind::kReport) {
    if (event.kind != RawEventKind::kRemoved) ++counters_.unknown_reports;
    return;
  }
  // A truncated report was cut at 64 bytes: its records cannot be trusted
  // to be the ones the device sent together.
  if (event.size == 0 || event.size % kEvdevRecordBytes != 0 || event.truncated) {
    ++(event.size < kEvdevRecordBytes ? counters_.short_reports : counters_.invalid_reports);
    return;
  }
  for (size_t at = 0; at < event.size; at += kEvdevRecordBytes)
    take(decode_evdev_record(event.data.data() + at), event.t_ns, out);
}

void EvdevEventParser::take(const EvdevRecord& r, int64_t t_ns, std::vector<InputEvent>& out) {
  if (r.type == EV_SYN && r.code == SYN_DROPPED) {
    ++overruns_;
    dropping_ = true;
    return;
  }
  if (r.type == EV_SYN && r.code == SYN_REPORT) {
    if (dropping_) {
      // The frame the overrun cut is lost as a whole; the backend's resync
      // frame that follows brings the state back.
      dropping_ = false;
      pending_ = value_;
      for (size_t i = 0; i < 6; ++i) {
        if (layout_.axes[i].kind == EvdevAxisKind::kRelative) pending_[i] = 0;
      }
      pending_buttons_ = buttons_;
      button_order_.clear();
      axes_touched_ = false;
      return;
    }
    end_frame(t_ns, out);
    return;
  }
  if (dropping_) return;
  if ((r.type == EV_ABS || r.type == EV_REL) && r.code < 6) {
    const EvdevAxisKind want =
        r.type == EV_ABS ? EvdevAxisKind::kAbsolute : EvdevAxisKind::kRelative;
    if (layout_.axes[r.code].kind != want) {
      ++counters_.unknown_reports;
      return;
    }
    pending_[r.code] = r.value;
    axes_touched_ = true;
    return;
  }
  if (r.type == EV_KEY) {
    const int b = button_index(r.code);
    if (b < 0 || r.value == 2) return;  // not a button of this device; 2 is autorepeat
    const uint32_t bit = 1u << b;
    const uint32_t before = pending_buttons_;
    pending_buttons_ = r.value != 0 ? pending_buttons_ | bit : pending_buttons_ & ~bit;
    if (pending_buttons_ != before &&
        std::find(button_order_.begin(), button_order_.end(), b) == button_order_.end())
      button_order_.push_back(b);
    return;
  }
  // EV_MSC scan codes and the like: nothing the station uses.
}

void EvdevEventParser::end_frame(int64_t t_ns, std::vector<InputEvent>& out) {
  const std::array<int32_t, 6> before = value_;
  value_ = pending_;
  // A relative axis is 0 unless this frame moved it.
  for (size_t i = 0; i < 6; ++i) {
    if (layout_.axes[i].kind == EvdevAxisKind::kRelative) pending_[i] = 0;
  }
  if (axes_touched_ || value_ != before) {
    InputEvent e;
    e.kind = InputKind::kMotion;
    e.t_ns = t_ns;
    for (int i = 0; i < 6; ++i) {
      const uint8_t src = mapping_.axis_source[i] < 6 ? mapping_.axis_source[i] : 0;
      e.axes[i] =
          normalised(value_[src], layout_.axes[src]) * static_cast<float>(mapping_.axis_sign[i]);
    }
    out.push_back(e);
  }
  axes_touched_ = false;
  for (int b : button_order_) {
    const bool pressed = (pending_buttons_ >> b) & 1u;
    if (pressed == (((buttons_ >> b) & 1u) != 0)) continue;  // pressed and released in one frame
    InputEvent e;
    e.kind = InputKind::kButton;
    e.t_ns = t_ns;
    e.button = b;
    e.pressed = pressed;
    out.push_back(e);
  }
  button_order_.clear();
  buttons_ = pending_buttons_;
}

}  // namespace sculpt::hal
