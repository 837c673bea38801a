#include "sculpt/hal/parsers/tracker_report_parser.h"

#include "sculpt/hal/parsers/opentrack_datagram.h"
#include "sculpt/hal/parsers/vrpn_message.h"

namespace sculpt::hal {
namespace {

// Short bytes are counted as short (as the HID parsers do); every other
// refusal drops the whole report, since a pose cannot be used in part.
bool decode(TrackerFormat format, std::span<const uint8_t> bytes, TrackerPose& pose,
            ParserCounters& counters) {
  if (format == TrackerFormat::kOpenTrack) {
    const OpenTrackDatagramError e = decode_opentrack_datagram(bytes, pose);
    if (e == OpenTrackDatagramError::kNone) return true;
    ++(e == OpenTrackDatagramError::kShort ? counters.short_reports : counters.invalid_reports);
    return false;
  }
  const VrpnPayloadError e = decode_vrpn_pos_quat(bytes, pose);
  if (e == VrpnPayloadError::kNone) return true;
  ++(e == VrpnPayloadError::kShort ? counters.short_reports : counters.invalid_reports);
  return false;
}

}  // namespace

void TrackerReportParser::parse(const RawEvent& event, std::vector<InputEvent>& out) {
  ++counters_.reports;
  if (event.kind != RawEventKind::kReport) {
    // Trackers deliver reports only; a removal becomes kDisconnected upstream.
    if (event.kind != RawEventKind::kRemoved) ++counters_.unknown_reports;
    return;
  }
  InputEvent e;
  e.t_ns = event.t_ns;
  if (event.size == 0) {
    e.kind = InputKind::kTrackingLost;
    out.push_back(e);
    return;
  }
  // A truncated report was longer than any pose: decoding its first 64
  // bytes would accept bytes the tracker did not send as one pose.
  if (event.truncated) {
    ++counters_.invalid_reports;
    return;
  }
  if (!decode(format_, event.bytes(), e.pose, counters_)) return;
  e.kind = InputKind::kMotion;
  e.absolute = true;
  e.has_pose = true;
  out.push_back(e);
}

}  // namespace sculpt::hal
