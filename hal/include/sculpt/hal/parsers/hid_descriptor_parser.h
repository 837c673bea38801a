#pragma once
// The generic parser: any HID multi-axis controller (usage page 1, usage 8)
// read through its report descriptor. Relative axes are scaled by the larger
// magnitude of their logical range (deflection in [-1, 1]); absolute axes are
// mapped from [min, max] to [-1, 1] and flagged absolute (position control).
// HID axes follow the HID frame (+Y toward the user, +Z down) like the
// 3Dconnexion devices, so the same frame change is applied.

#include <bitset>

#include "sculpt/hal/parsers/hid_descriptor.h"
#include "sculpt/hal/parsers/report_parser.h"

namespace sculpt::hal {

class HidDescriptorParser final : public ReportParser {
 public:
  explicit HidDescriptorParser(HidLayout layout);
  void parse(const RawEvent& event, std::vector<InputEvent>& out) override;
  const HidLayout& layout() const { return layout_; }

 private:
  HidLayout layout_;
  std::array<float, 6> hid_axes_{};  // HID frame
  std::array<bool, 6> fresh_{};
  std::bitset<128> buttons_;
};

}  // namespace sculpt::hal
