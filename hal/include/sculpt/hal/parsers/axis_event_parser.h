#pragma once
// The parser for backends that deliver decoded axes (spacenavd, or a replay
// of them): kAxis events accumulate, kSync closes one motion sample, kButton
// events pass through. spacenavd's frame is +X right, +Y up, +Z away from the
// user, so z and rz are negated into the station frame.

#include <array>

#include "sculpt/hal/parsers/report_parser.h"

namespace sculpt::hal {

class AxisEventParser final : public ReportParser {
 public:
  /// full_scale: counts at full deflection (spacenavd passes the device's ±350).
  explicit AxisEventParser(float full_scale = 350.0f,
                           std::array<int8_t, 6> sign = {1, 1, -1, 1, 1, -1});
  void parse(const RawEvent& event, std::vector<InputEvent>& out) override;

 private:
  float full_scale_;
  std::array<int8_t, 6> sign_;
  std::array<int, 6> counts_{};
  bool dirty_ = false;
};

}  // namespace sculpt::hal
