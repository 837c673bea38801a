#include "sculpt/hal/parsers/axis_event_parser.h"

#include <algorithm>

namespace sculpt::hal {

AxisEventParser::AxisEventParser(float full_scale, std::array<int8_t, 6> sign)
    : full_scale_(full_scale > 0 ? full_scale : 1.0f), sign_(sign) {}

void AxisEventParser::parse(const RawEvent& event, std::vector<InputEvent>& out) {
  ++counters_.reports;
  switch (event.kind) {
    case RawEventKind::kAxis:
      if (event.index < 0 || event.index >= 6) {
        ++counters_.unknown_reports;
        return;
      }
      counts_[event.index] = event.value;
      dirty_ = true;
      return;
    case RawEventKind::kSync: {
      if (!dirty_) return;
      InputEvent e;
      e.kind = InputKind::kMotion;
      e.t_ns = event.t_ns;
      for (int i = 0; i < 6; ++i) {
        e.axes[i] =
            std::clamp(static_cast<float>(counts_[i]) / full_scale_ * sign_[i], -1.0f, 1.0f);
      }
      out.push_back(e);
      dirty_ = false;
      return;
    }
    case RawEventKind::kButton: {
      InputEvent e;
      e.kind = InputKind::kButton;
      e.t_ns = event.t_ns;
      e.button = event.index;
      e.pressed = event.value != 0;
      out.push_back(e);
      return;
    }
    case RawEventKind::kReport:
      ++counters_.unknown_reports;
      return;
    case RawEventKind::kRemoved:
      return;
  }
}

}  // namespace sculpt::hal
