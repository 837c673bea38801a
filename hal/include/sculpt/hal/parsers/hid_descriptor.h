#pragma once
// A HID report descriptor parser (HID 1.11 §6.2.2) reduced to what a 6-DOF
// device needs: the input fields of the generic desktop axes X Y Z Rx Ry Rz
// and of the buttons, with their report id, bit position, size, logical range
// and whether they are relative or absolute.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "sculpt/base/result.h"

namespace sculpt::hal {

struct HidField {
  uint8_t report_id = 0;    ///< 0 when the descriptor does not number its reports
  uint32_t bit_offset = 0;  ///< from the first data byte (after the id byte when numbered)
  uint32_t bit_size = 0;    ///< 1..32
  int32_t logical_min = 0;
  int32_t logical_max = 0;
  bool relative = false;
  uint16_t usage_page = 0;
  uint16_t usage = 0;  ///< page 1: 0x30 X .. 0x35 Rz; page 9: button number from 1
};

struct HidLayout {
  uint16_t usage_page = 0;  ///< of the first application collection
  uint16_t usage = 0;
  bool numbered_reports = false;  ///< a Report ID item appears
  /// Axis fields in the order tx ty tz rx ry rz; absent axes have no value.
  std::array<std::optional<HidField>, 6> axes;
  std::vector<HidField> buttons;  ///< one field per button, button = usage - 1

  /// Usage page 1, usage 8 with at least one axis.
  bool is_multi_axis_controller() const;
};

/// Parses a report descriptor. Errors name the byte offset and what is wrong
/// ("report descriptor: byte 17: item runs past the end").
Result<HidLayout> parse_hid_descriptor(std::span<const uint8_t> descriptor);

/// Reads `bit_size` bits at `bit_offset` of `data` (LSB first, as HID does),
/// sign-extended when the field's logical minimum is negative. nullopt when the
/// data is too short.
std::optional<int32_t> extract_hid_field(std::span<const uint8_t> data, const HidField& field);

}  // namespace sculpt::hal
