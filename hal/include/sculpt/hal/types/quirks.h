#pragma once
// The device quirks table (a data table keyed by vendor:product, after
// spacenavd's usbdb): which 3Dconnexion devices we know, how their reports are
// laid out, how their axes and buttons map, and which IDs to ignore.

#include <array>
#include <cstdint>
#include <span>
#include <string_view>

namespace sculpt::hal {

enum class QuirkKind : uint8_t {
  kSpaceMouse,  ///< a 3Dconnexion 6-DOF device, read with SpaceMouseParser
  kIgnore,      ///< same vendor, not a 6-DOF device (CadMouse, keyboards): never opened
};

enum class MotionLayout : uint8_t {
  kSplit,     ///< report 1: tx ty tz; report 2: rx ry rz (int16 LE each)
  kCombined,  ///< report 1: all six axes, 13 bytes
};

enum class ButtonForm : uint8_t {
  kBitmask,   ///< report 3: one bit per button
  kNumbered,  ///< report 0x1c: the numbers (from 1) of the buttons held, 0 pads
};

struct DeviceQuirks {
  uint16_t vendor_id = 0;
  uint16_t product_id = 0;
  std::string_view name;
  QuirkKind kind = QuirkKind::kSpaceMouse;
  MotionLayout layout = MotionLayout::kSplit;
  ButtonForm buttons = ButtonForm::kBitmask;
  /// Counts at full deflection (the devices report about ±350).
  int16_t axis_range = 350;
  /// Output axis i (tx ty tz rx ry rz, station frame) = axis_sign[i] * raw
  /// axis axis_source[i]. The default turns the HID frame (+Y toward the user,
  /// +Z down) into the station's (+Y up, +Z toward the user).
  std::array<uint8_t, 6> axis_source{0, 2, 1, 3, 5, 4};
  std::array<int8_t, 6> axis_sign{1, -1, 1, 1, -1, 1};
  /// Bit (or number - 1) of the raw button report -> logical button; empty:
  /// identity. Compacts the sparse layouts of the bigger devices.
  std::span<const uint8_t> button_map;
  /// The device has several HID interfaces (the Universal Receiver also
  /// presents a mouse): open only the one with usage page 1, usage 8.
  bool multi_axis_interface_only = false;
  bool has_battery = false;
};

/// The quirks of vendor:product, or nullptr for a device not in the table.
const DeviceQuirks* find_quirks(uint16_t vendor_id, uint16_t product_id);

/// The whole table, for listing and tests.
std::span<const DeviceQuirks> all_quirks();

/// True when the device must not be opened: an ignored ID, or a known
/// device's interface that is not its multi-axis one (usage known and not 1:8).
bool is_ignored(uint16_t vendor_id, uint16_t product_id, uint16_t usage_page, uint16_t usage);

}  // namespace sculpt::hal
