#pragma once
// The parser for trackers (OpenTrack, VRPN): each report holds the bytes of
// one datagram or Pos_Quat payload, decoded again here, so a live tracker and
// a replay of its session give the same pose events.
//
// A report with bytes gives one absolute kMotion event with has_pose set
// (TrackerPose: mm, unit quaternion w x y z, the tracker's frame). A report
// with no bytes is the backend's "tracking lost": one kTrackingLost event.
// Bad bytes (short, long, NaN, not a rotation) are counted and dropped.

#include "sculpt/hal/parsers/report_parser.h"

namespace sculpt::hal {

enum class TrackerFormat : uint8_t {
  kOpenTrack,  ///< 48-byte "UDP over network" datagrams
  kVrpn,       ///< 64-byte vrpn_Tracker Pos_Quat payloads
};

class TrackerReportParser final : public ReportParser {
 public:
  explicit TrackerReportParser(TrackerFormat format) : format_(format) {}
  void parse(const RawEvent& event, std::vector<InputEvent>& out) override;

 private:
  TrackerFormat format_;
};

}  // namespace sculpt::hal
