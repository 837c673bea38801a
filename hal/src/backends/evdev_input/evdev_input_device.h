#pragma once
// A Linux evdev 6-axis device (/dev/input/eventN with X Y Z RX RY RZ, each
// EV_ABS or EV_REL, and its buttons) as a Device, over the evdev edge of
// the force-feedback backend (evdev_ff/evdev_io.h), so the tests drive it
// through a byte-level fake of the kernel's event stream.
//
// What it delivers: kReport RawEvents holding 1..8 EvdevRecords (type, code,
// value of the input_events the node gave, only SYN, the six axes and the
// layout's buttons; parsers/evdev_event_parser.h), cut after each
// SYN_REPORT; DeviceInfo::report_descriptor holds the EvdevLayout. So a
// session records what the device said and a replay parses it again.
//
// Frames it adds, recorded like the device's own: at open, the device's
// whole state (absolute axes and held buttons, then SYN_REPORT); after the
// SYN_REPORT that ends an overrun (SYN_DROPPED), the same state frame read
// again with EVIOCGABS/EVIOCGKEY (event-codes.rst's resync); and for a
// device with relative axes, an empty frame (a lone SYN_REPORT) once no
// event came for rel_release_ms after one that moved: the kernel never
// passes a relative 0 on, so a released cap would otherwise keep moving
// the tool.
//
// Errors: ENODEV (or any failure of poll or read but EAGAIN) ends the
// device: what was read is delivered, then kRemoved. Bytes that make no
// whole input_event are counted and dropped, with one log line per device.

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "backends/evdev_ff/evdev_io.h"
#include "sculpt/base/result.h"
#include "sculpt/hal/parsers/evdev_event_parser.h"
#include "sculpt/hal/types/device.h"

namespace sculpt::hal::evdev_input {

struct EvdevInputOptions {
  /// Full scale of a relative axis, counts (3Dconnexion devices report
  /// about +-350 when they report relative axes, as spacenavd assumes).
  int32_t relative_full_scale = 350;
  /// Silence after a relative frame that means "released", ms.
  int rel_release_ms = 60;
  /// Where the one line per problem goes; stderr when empty.
  std::function<void(std::string_view)> log;
};

struct EvdevInputCounters {
  int64_t events = 0;       ///< input_event records read
  int64_t frames = 0;       ///< SYN_REPORTs read
  int64_t overruns = 0;     ///< SYN_DROPPED read (a state frame follows)
  int64_t stray_bytes = 0;  ///< bytes that made no whole input_event, dropped
  int64_t releases = 0;     ///< empty frames added for a released relative device
  int64_t reports = 0;      ///< kReport RawEvents delivered
};

/// Why a node is not a 6-axis device, or the layout it has. `ev`, `abs`,
/// `rel`, `keys` are capability bits (evdev_io.h's bit order); `props` the
/// input properties (may be empty).
Result<EvdevLayout> evdev_6axis_layout(std::span<const uint8_t> ev, std::span<const uint8_t> abs,
                                       std::span<const uint8_t> rel, std::span<const uint8_t> keys,
                                       std::span<const uint8_t> props,
                                       const EvdevInputOptions& options = {});

/// The 6-axis event nodes `io` lists (DeviceInfo::backend "evdev", path
/// "/dev/input/eventN", usb_location and serial (uniq) from sysfs, so the
/// registry can tell the same physical device seen through hidraw). Nodes
/// sysfs rules out are not opened; a 6-axis node this user may not open is
/// listed with accessible = false. Leaves `io` closed.
std::vector<DeviceInfo> list_evdev_6axis_devices(evdev_ff::EvdevIo& io,
                                                 const EvdevInputOptions& options = {});

class EvdevInputDevice final : public Device {
 public:
  /// Opens `path` through `io` and reads its layout and state. Errors name
  /// the path: not 6-axis (and why), no permission (how to get it), gone.
  static Result<std::unique_ptr<EvdevInputDevice>> open(std::unique_ptr<evdev_ff::EvdevIo> io,
                                                        const std::string& path,
                                                        EvdevInputOptions options = {});
  ~EvdevInputDevice() override;
  EvdevInputDevice(const EvdevInputDevice&) = delete;
  EvdevInputDevice& operator=(const EvdevInputDevice&) = delete;

  const DeviceInfo& info() const override { return info_; }
  ReadResult read(RawEvent& out, int timeout_ms) override;

  const EvdevLayout& layout() const { return layout_; }
  const EvdevInputCounters& counters() const { return counters_; }

 private:
  EvdevInputDevice(std::unique_ptr<evdev_ff::EvdevIo> io, EvdevInputOptions options);
  // Queues the device's state as one frame; false when it cannot be read.
  bool queue_state_frame();
  void queue(const EvdevRecord& r);
  void flush();  // closes the report being filled
  void take(const input_event& ev);
  void end(const std::string& why);
  void log(const std::string& line);

  std::unique_ptr<evdev_ff::EvdevIo> io_;
  EvdevInputOptions options_;
  DeviceInfo info_;
  EvdevLayout layout_;
  std::vector<EvdevRecord> filling_;  // records of the report being built
  std::deque<RawEvent> ready_;
  int64_t now_ns_ = 0;  // arrival time of what is being read
  bool dropping_ = false;
  bool relative_moving_ = false;  // the last frame moved a relative axis
  bool frame_moved_relative_ = false;
  int64_t last_frame_ns_ = 0;
  bool removed_ = false;
  bool stray_logged_ = false;
  EvdevInputCounters counters_;
};

}  // namespace sculpt::hal::evdev_input
