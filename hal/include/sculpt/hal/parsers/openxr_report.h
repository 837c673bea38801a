#pragma once
// What the OpenXR backend records of a controller, one kReport per change,
// and its parser: so a live controller and the replay of its session give
// the same events.
//
// Report, 64 bytes, little-endian: byte 0 'X' (the format), byte 1 flags
// (bit 0: the grip pose is tracked), bytes 2..3 the buttons held (bit 0
// trigger past half, bit 1 select, bit 2 menu, bit 3 squeeze), bytes 4..7
// the trigger value (float32, 0..1), bytes 8..31 the grip position in mm
// (three float64, OpenXR's frame: +X right, +Y up, +Z toward the user),
// bytes 32..63 its orientation, a quaternion w, x, y, z (four float64).
//
// The parser gives an absolute kMotion with has_pose for each tracked pose
// (the quaternion normalised here, so replay and live agree), kButton for
// each button that changed, and kTrackingLost when tracking stops. Bad
// reports (wrong size or format byte, not finite, a zero quaternion) are
// counted and dropped.

#include <array>
#include <cstdint>
#include <span>

#include "sculpt/hal/parsers/report_parser.h"
#include "sculpt/hal/types/tracker_pose.h"

namespace sculpt::hal {

inline constexpr size_t kOpenXrReportBytes = 64;

struct OpenXrControllerState {
  bool tracked = false;
  uint16_t buttons = 0;  ///< bit 0 trigger, 1 select, 2 menu, 3 squeeze
  float trigger = 0.0f;
  std::array<double, 3> position_mm{};
  std::array<double, 4> quat_wxyz{1, 0, 0, 0};
};

std::array<uint8_t, kOpenXrReportBytes> encode_openxr_report(const OpenXrControllerState& state);

enum class OpenXrReportError : uint8_t { kNone, kSize, kFormat, kNotFinite, kNotRotation };

/// On kNone `out` holds the state with the quaternion normalised (when tracked).
OpenXrReportError decode_openxr_report(std::span<const uint8_t> bytes, OpenXrControllerState& out);

class OpenXrReportParser final : public ReportParser {
 public:
  void parse(const RawEvent& event, std::vector<InputEvent>& out) override;

 private:
  uint16_t buttons_ = 0;
  bool tracked_ = false;
};

}  // namespace sculpt::hal
