#include "sculpt/hal/parsers/make_parser.h"

#include "sculpt/hal/parsers/axis_event_parser.h"
#include "sculpt/hal/parsers/evdev_event_parser.h"
#include "sculpt/hal/parsers/hid_descriptor_parser.h"
#include "sculpt/hal/parsers/openxr_report.h"
#include "sculpt/hal/parsers/spacemouse_parser.h"
#include "sculpt/hal/parsers/tracker_report_parser.h"
#include "sculpt/hal/types/quirks.h"

namespace sculpt::hal {

Result<std::unique_ptr<ReportParser>> make_parser(const DeviceInfo& info) {
  const std::string who = info.id() + " (" + info.vendor_product() + ")";
  // spacenavd has decoded the device already, whatever it is.
  if (info.backend == "spnav")
    return std::unique_ptr<ReportParser>(std::make_unique<AxisEventParser>());
  // A tracker's reports are its datagrams or messages, whatever it tracks.
  if (info.backend == "opentrack")
    return std::unique_ptr<ReportParser>(
        std::make_unique<TrackerReportParser>(TrackerFormat::kOpenTrack));
  if (info.backend == "vrpn")
    return std::unique_ptr<ReportParser>(
        std::make_unique<TrackerReportParser>(TrackerFormat::kVrpn));
  if (info.backend == "openxr")
    return std::unique_ptr<ReportParser>(std::make_unique<OpenXrReportParser>());
  // An evdev device is described by its recorded layout, whatever it is;
  // a known 3D mouse keeps its table row's axis mapping.
  if (info.backend == "evdev") {
    EvdevLayout layout;
    const EvdevLayoutError e = decode_evdev_layout(info.report_descriptor, layout);
    if (e != EvdevLayoutError::kNone) return Error(who + ": " + std::string(describe(e)));
    const DeviceQuirks* q = find_quirks(info.vendor_id, info.product_id);
    if (q && q->kind != QuirkKind::kSpaceMouse) q = nullptr;
    return std::unique_ptr<ReportParser>(std::make_unique<EvdevEventParser>(std::move(layout), q));
  }
  if (const DeviceQuirks* q = find_quirks(info.vendor_id, info.product_id)) {
    if (q->kind == QuirkKind::kIgnore) {
      return Error(who + ": " + std::string(q->name) + " is not a 6-DOF device");
    }
    return std::unique_ptr<ReportParser>(std::make_unique<SpaceMouseParser>(*q));
  }
  if (info.report_descriptor.empty()) {
    return Error(who + ": unknown device and no HID report descriptor to read it by");
  }
  auto layout = parse_hid_descriptor(info.report_descriptor);
  if (!layout) return layout.error().in(who);
  if (!layout->is_multi_axis_controller()) {
    return Error(who + ": not a multi-axis controller (usage page " +
                 std::to_string(layout->usage_page) + " usage " + std::to_string(layout->usage) +
                 ", want page 1 usage 8 with axes)");
  }
  return std::unique_ptr<ReportParser>(
      std::make_unique<HidDescriptorParser>(std::move(layout).value()));
}

}  // namespace sculpt::hal
