#include "sculpt/hal/parsers/hid_descriptor_parser.h"

#include <algorithm>
#include <cstdlib>

namespace sculpt::hal {
namespace {

// The HID frame (+Y toward the user, +Z down) to the station frame (+Y up,
// +Z toward the user), as for the 3Dconnexion devices.
constexpr std::array<int, 6> kSource{0, 2, 1, 3, 5, 4};
constexpr std::array<float, 6> kSign{1, -1, 1, 1, -1, 1};

}  // namespace

HidDescriptorParser::HidDescriptorParser(HidLayout layout) : layout_(std::move(layout)) {}

void HidDescriptorParser::parse(const RawEvent& event, std::vector<InputEvent>& out) {
  if (event.kind != RawEventKind::kReport) return;
  ++counters_.reports;
  std::span<const uint8_t> b = event.bytes();
  uint8_t id = 0;
  if (layout_.numbered_reports) {
    if (b.empty()) {
      ++counters_.short_reports;
      return;
    }
    id = b[0];
    b = b.subspan(1);
  }
  if (event.truncated) ++counters_.overlong_reports;
  // A report too short for any of its fields is malformed as a whole: using
  // the fields that fit would mix new and old axes.
  bool known_id = false;
  auto fits = [&](const HidField& f) {
    if (f.report_id != id) return true;
    known_id = true;
    return uint64_t{f.bit_offset} + f.bit_size <= uint64_t{b.size()} * 8;
  };
  bool all_fit = true;
  for (const auto& f : layout_.axes)
    all_fit &= !f || fits(*f);
  for (const HidField& f : layout_.buttons)
    all_fit &= fits(f);
  if (known_id && !all_fit) {
    ++counters_.short_reports;
    return;
  }
  bool any_axis = false, any_field = false, absolute = false;
  for (int a = 0; a < 6; ++a) {
    const auto& f = layout_.axes[a];
    if (!f || f->report_id != id) continue;
    any_field = true;
    const auto v = extract_hid_field(b, *f);
    if (!v) continue;
    float x = 0.0f;
    if (f->relative) {
      const float span =
          static_cast<float>(std::max(std::abs(f->logical_min), std::abs(f->logical_max)));
      x = span > 0 ? static_cast<float>(*v) / span : 0.0f;
    } else {
      const float lo = static_cast<float>(f->logical_min), hi = static_cast<float>(f->logical_max);
      x = hi > lo ? 2.0f * (static_cast<float>(*v) - lo) / (hi - lo) - 1.0f : 0.0f;
      absolute = true;
    }
    hid_axes_[a] = std::clamp(x, -1.0f, 1.0f);
    fresh_[a] = true;
    any_axis = true;
  }
  std::bitset<128> buttons = buttons_;
  bool button_field = false;
  for (const HidField& f : layout_.buttons) {
    if (f.report_id != id || f.usage > 128) continue;
    any_field = true;
    const auto v = extract_hid_field(b, f);
    if (!v) continue;
    button_field = true;
    buttons[f.usage - 1] = *v != 0;
  }
  if (!any_field) {
    ++counters_.unknown_reports;
    return;
  }
  if (any_axis) {
    InputEvent e;
    e.kind = InputKind::kMotion;
    e.t_ns = event.t_ns;
    e.absolute = absolute;
    bool t_fresh = true, r_fresh = true;
    for (int i = 0; i < 6; ++i) {
      const int src = kSource[i];
      e.axes[i] = hid_axes_[src] * kSign[i];
      if (layout_.axes[src]) (i < 3 ? t_fresh : r_fresh) &= fresh_[src];
    }
    // Devices that spread the axes over several reports: a sample whose other
    // half did not come in this report is flagged, like the split 3Dconnexion layout.
    e.translation_stale = !t_fresh;
    e.rotation_stale = !r_fresh;
    // Relative axes are deflections that hold until the next report; fresh
    // means "sent since the last sample".
    fresh_.fill(false);
    out.push_back(e);
  }
  if (button_field) {
    const std::bitset<128> changed = buttons ^ buttons_;
    for (int k = 0; k < 128; ++k) {
      if (!changed[k]) continue;
      InputEvent e;
      e.kind = InputKind::kButton;
      e.t_ns = event.t_ns;
      e.button = k;
      e.pressed = buttons[k];
      out.push_back(e);
    }
    buttons_ = buttons;
  }
}

}  // namespace sculpt::hal
