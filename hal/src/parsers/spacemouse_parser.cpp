#include "sculpt/hal/parsers/spacemouse_parser.h"

#include <algorithm>

namespace sculpt::hal {
namespace {

int16_t le16(std::span<const uint8_t> b, size_t at) {
  return static_cast<int16_t>(b[at] | (b[at + 1] << 8));
}

constexpr size_t kSplitSize = 7;      // id + 3 x int16
constexpr size_t kCombinedSize = 13;  // id + 6 x int16

}  // namespace

SpaceMouseParser::SpaceMouseParser(const DeviceQuirks& quirks) : quirks_(quirks) {}

void SpaceMouseParser::emit_motion(int64_t t_ns, bool translation_stale, bool rotation_stale,
                                   std::vector<InputEvent>& out) {
  InputEvent e;
  e.kind = InputKind::kMotion;
  e.t_ns = t_ns;
  e.translation_stale = translation_stale;
  e.rotation_stale = rotation_stale;
  const float scale = 1.0f / static_cast<float>(std::max<int16_t>(quirks_.axis_range, 1));
  for (int i = 0; i < 6; ++i) {
    const float v = static_cast<float>(raw_[quirks_.axis_source[i]]) * scale * quirks_.axis_sign[i];
    e.axes[i] = std::clamp(v, -1.0f, 1.0f);
  }
  out.push_back(e);
  translation_fresh_ = rotation_fresh_ = false;
}

void SpaceMouseParser::set_buttons(int64_t t_ns, const std::bitset<kMaxButtons>& raw,
                                   std::vector<InputEvent>& out) {
  const std::bitset<kMaxButtons> changed = raw ^ buttons_;
  buttons_ = raw;
  for (int bit = 0; bit < kMaxButtons; ++bit) {
    if (!changed[bit]) continue;
    int logical = bit;
    if (!quirks_.button_map.empty()) {
      // Bits the map does not name are not buttons on this device (status
      // bits): ignored rather than invented.
      if (static_cast<size_t>(bit) >= quirks_.button_map.size() || quirks_.button_map[bit] == 255)
        continue;
      logical = quirks_.button_map[bit];
    }
    InputEvent e;
    e.kind = InputKind::kButton;
    e.t_ns = t_ns;
    e.button = logical;
    e.pressed = raw[bit];
    out.push_back(e);
  }
}

void SpaceMouseParser::parse(const RawEvent& event, std::vector<InputEvent>& out) {
  if (event.kind != RawEventKind::kReport) return;
  ++counters_.reports;
  const std::span<const uint8_t> b = event.bytes();
  if (b.empty()) {
    ++counters_.short_reports;
    return;
  }
  if (event.truncated) ++counters_.overlong_reports;
  const int64_t t = event.t_ns;
  switch (b[0]) {
    case kTranslationReport: {
      if (b.size() < kSplitSize) {
        ++counters_.short_reports;
        return;
      }
      // The length tells the layout: a 13-byte report 1 carries all six axes
      // even on a device the table lists as split (firmware revisions differ).
      if (b.size() >= kCombinedSize) {
        if (b.size() > kCombinedSize) ++counters_.overlong_reports;
        for (int i = 0; i < 6; ++i)
          raw_[i] = le16(b, 1 + 2 * i);
        emit_motion(t, false, false, out);
        return;
      }
      if (b.size() > kSplitSize) ++counters_.overlong_reports;
      // The same half twice in a row: the other half was lost or the device
      // only sends what changed. Emit what we have, flagged, rather than
      // stalling the motion.
      if (translation_fresh_) emit_motion(pending_t_ns_, false, true, out);
      for (int i = 0; i < 3; ++i)
        raw_[i] = le16(b, 1 + 2 * i);
      translation_fresh_ = true;
      pending_t_ns_ = t;
      if (rotation_fresh_) emit_motion(t, false, false, out);
      return;
    }
    case kRotationReport: {
      if (b.size() < kSplitSize) {
        ++counters_.short_reports;
        return;
      }
      if (b.size() > kSplitSize) ++counters_.overlong_reports;
      if (rotation_fresh_) emit_motion(pending_t_ns_, true, false, out);
      for (int i = 0; i < 3; ++i)
        raw_[3 + i] = le16(b, 1 + 2 * i);
      rotation_fresh_ = true;
      pending_t_ns_ = t;
      if (translation_fresh_) emit_motion(t, false, false, out);
      return;
    }
    case kButtonReport: {
      if (b.size() < 2) {
        ++counters_.short_reports;
        return;
      }
      std::bitset<kMaxButtons> raw;
      const size_t bytes = std::min<size_t>(b.size() - 1, kMaxButtons / 8);
      if (b.size() - 1 > bytes) ++counters_.overlong_reports;
      for (size_t i = 0; i < bytes; ++i) {
        for (int bit = 0; bit < 8; ++bit)
          raw[i * 8 + bit] = (b[1 + i] >> bit) & 1;
      }
      set_buttons(t, raw, out);
      return;
    }
    case kNumberedButtonReport: {
      if (b.size() < 2) {
        ++counters_.short_reports;
        return;
      }
      std::bitset<kMaxButtons> raw;
      for (size_t i = 1; i < b.size(); ++i) {
        if (b[i] == 0) continue;  // padding
        if (b[i] > kMaxButtons) {
          ++counters_.overlong_reports;
          continue;
        }
        raw[b[i] - 1] = true;
      }
      set_buttons(t, raw, out);
      return;
    }
    case kBatteryReport: {
      if (b.size() < 2) {
        ++counters_.short_reports;
        return;
      }
      InputEvent e;
      e.kind = InputKind::kBattery;
      e.t_ns = t;
      e.battery_percent = std::min<int>(b[1], 100);
      e.charging = b.size() >= 3 && (b[2] & 1) != 0;
      out.push_back(e);
      return;
    }
    default:
      // LED state echoes, vendor feature reports and the like.
      ++counters_.unknown_reports;
      return;
  }
}

}  // namespace sculpt::hal
