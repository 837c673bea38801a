// libFuzzer target: the reports a session holds for an OpenXR controller,
// through decode_openxr_report() and OpenXrReportParser as a replay runs
// them. Input: chunks, each a length byte and that many bytes as one
// report. Checks: no crash; a report is accepted only at 64 bytes and then
// encodes back to a report that decodes the same; an accepted tracked pose
// is finite with a unit quaternion; the parser gives motion with a pose,
// buttons 0..15 and tracking lost only. Seeds: corpus/openxr_report.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "sculpt/hal/parsers/openxr_report.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace sculpt::hal;
  OpenXrReportParser parser;
  std::vector<InputEvent> out;
  size_t at = 0;
  while (at < size) {
    const size_t n = std::min<size_t>(data[at], size - at - 1);
    const std::span<const uint8_t> bytes(data + at + 1, n);
    at += 1 + n;
    OpenXrControllerState s;
    if (decode_openxr_report(bytes, s) == OpenXrReportError::kNone) {
      if (n != kOpenXrReportBytes) __builtin_trap();
      OpenXrControllerState again;
      if (decode_openxr_report(encode_openxr_report(s), again) != OpenXrReportError::kNone ||
          again.buttons != s.buttons || again.tracked != s.tracked)
        __builtin_trap();
      TrackerPose pose;
      pose.position_mm = s.position_mm;
      pose.quat_wxyz = s.quat_wxyz;
      if (s.tracked && !is_finite_unit_pose(pose, 1e-6)) __builtin_trap();
    }
    parser.parse(RawEvent::report(static_cast<int64_t>(at), bytes), out);
  }
  for (const InputEvent& e : out) {
    if (e.kind == InputKind::kMotion) {
      if (!e.has_pose || !is_finite_unit_pose(e.pose, 1e-6)) __builtin_trap();
    } else if (e.kind == InputKind::kButton) {
      if (e.button < 0 || e.button > 15) __builtin_trap();
    } else if (e.kind != InputKind::kTrackingLost) {
      __builtin_trap();
    }
  }
  return 0;
}
