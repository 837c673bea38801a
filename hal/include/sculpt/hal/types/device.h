#pragma once
// The device model (DESIGN.md §5): a Backend is a transport that enumerates
// and opens devices; a Device is one open handle that delivers RawEvents.
//
// Thread safety: a Backend's enumerate()/open()/changed() are called from the
// main thread only. A Device is used by exactly one thread at a time (its
// reader thread); it is created on the main thread and handed over.
//
// Implementing a backend (the sim replay backend of the sessions issue does
// this): derive from Backend and Device; read() must return kRemoved exactly
// once when the device is gone and after that keep returning kRemoved. The
// RawEvents it produces go through the same parsers and normaliser as live
// input (see make_parser() and MotionPipeline), so a backend that is fed
// recorded reports with their recorded t_ns reproduces a live session.
// FeedBackend (backends/feed_backend.h) is a ready-made one.

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "sculpt/base/result.h"
#include "sculpt/hal/types/device_info.h"
#include "sculpt/hal/types/raw_event.h"

namespace sculpt::hal {

enum class ReadResult {
  kEvent,    ///< `out` holds one event
  kTimeout,  ///< nothing arrived within the timeout
  kRemoved,  ///< the device is gone (unplugged, daemon quit); `out` is a kRemoved event
};

class Device {
 public:
  virtual ~Device() = default;
  virtual const DeviceInfo& info() const = 0;
  /// Waits up to timeout_ms (0: do not wait) for the next event.
  virtual ReadResult read(RawEvent& out, int timeout_ms) = 0;
};

enum class BackendState {
  kReady,        ///< enumeration works (it may still find nothing)
  kNotBuilt,     ///< compiled without this backend (SCULPT_WITH_* off or library missing)
  kUnavailable,  ///< built, but the system does not offer it (no daemon, no USB access)
};

struct BackendStatus {
  BackendState state = BackendState::kReady;
  std::string note;  ///< why it is not ready, in one line
};

class Backend {
 public:
  virtual ~Backend() = default;
  /// "hidapi", "libusb", "spnav", "sim".
  virtual std::string_view name() const = 0;
  virtual BackendStatus status() = 0;
  /// The 6-DOF devices this transport sees (ignored IDs left out). An Error
  /// only when enumeration itself fails.
  virtual Result<std::vector<DeviceInfo>> enumerate() = 0;
  virtual Result<std::unique_ptr<Device>> open(const DeviceInfo& info) = 0;
  /// True when devices may have come or gone since the last call (a hotplug
  /// notification, or always for backends that can only poll).
  virtual bool changed() { return true; }
};

}  // namespace sculpt::hal
