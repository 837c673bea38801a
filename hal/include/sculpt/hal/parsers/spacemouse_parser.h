#pragma once
// The 3Dconnexion family parser. Report layouts (little-endian int16 axes in
// the HID frame: +X right, +Y toward the user, +Z down):
//   report 1, 7 bytes:   id, tx, ty, tz                 (split layout, older devices)
//   report 2, 7 bytes:   id, rx, ry, rz                 (split layout)
//   report 1, 13 bytes:  id, tx, ty, tz, rx, ry, rz     (combined layout, newer devices)
//   report 3:            id, button bitmask (bit i = button i, LSB first)
//   report 0x1c:         id, numbers (from 1) of the buttons held, 0 pads (SpaceMouse Enterprise)
//   report 0x17:         id, battery percent, charging flag (wireless devices)
// The layout of report 1 is taken from its length, so a device whose firmware
// changed layout still works; the quirks give the default, the axis frame and
// the button map.

#include <array>
#include <bitset>

#include "sculpt/hal/parsers/report_parser.h"
#include "sculpt/hal/types/quirks.h"

namespace sculpt::hal {

class SpaceMouseParser final : public ReportParser {
 public:
  static constexpr uint8_t kTranslationReport = 1;
  static constexpr uint8_t kRotationReport = 2;
  static constexpr uint8_t kButtonReport = 3;
  static constexpr uint8_t kBatteryReport = 0x17;
  static constexpr uint8_t kNumberedButtonReport = 0x1c;
  static constexpr int kMaxButtons = 64;

  explicit SpaceMouseParser(const DeviceQuirks& quirks);
  void parse(const RawEvent& event, std::vector<InputEvent>& out) override;

 private:
  void emit_motion(int64_t t_ns, bool translation_stale, bool rotation_stale,
                   std::vector<InputEvent>& out);
  void set_buttons(int64_t t_ns, const std::bitset<kMaxButtons>& raw, std::vector<InputEvent>& out);

  DeviceQuirks quirks_;
  std::array<int, 6> raw_{};  // HID frame counts, tx ty tz rx ry rz
  bool translation_fresh_ = false;
  bool rotation_fresh_ = false;
  int64_t pending_t_ns_ = 0;
  std::bitset<kMaxButtons> buttons_;  // raw bits held
};

}  // namespace sculpt::hal
