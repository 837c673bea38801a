#pragma once
// openxr: one VR controller through the OpenXR loader (Debian's
// libopenxr-loader1) as a 6-DOF device: its grip pose (position control,
// like a tracker) and its trigger and buttons. `openxr` or `openxr:right`
// is the right hand, `openxr:left` the left.
//
// Opened only when asked for (`--device openxr`), like the network
// trackers: a session starts the runtime's service and takes its input,
// which an automatic scan should not do. `sculpt devices` lists the backend.
//
// A session normally needs a graphics binding; the station has no VR view,
// so the backend asks for XR_MND_headless (a session without graphics,
// offered by Monado) and XR_KHR_convert_timespec_time (to ask for poses
// "now" without a frame loop). A runtime without them is reported as
// needing a graphics binding and the backend is unavailable.
//
// With no runtime installed (no manifest where the loader looks:
// XR_RUNTIME_JSON, then active_runtime.json in $XDG_CONFIG_HOME/openxr/1,
// each of $XDG_CONFIG_DIRS/openxr/1 and /etc/openxr/1) status() is
// kUnavailable, "no OpenXR runtime", and the loader is not even called.
//
// Each change of the controller's state is one kReport (parsers/
// openxr_report.h) recorded in sessions and parsed again on replay.
//
// Thread safety: as every Backend and Device (types/device.h).

#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "sculpt/base/result.h"
#include "sculpt/hal/types/device.h"

namespace sculpt::hal {

struct OpenXrOptions {
  std::string hand = "right";  ///< "right" or "left"
  int sample_period_ms = 4;    ///< how often the pose is asked for (250 Hz)
  /// Where the one line per problem goes; stderr when empty.
  std::function<void(std::string_view)> log;
};

/// "openxr", "openxr:right", "openxr:left".
Result<OpenXrOptions> parse_openxr_spec(const std::string& spec);

/// The runtime manifest the loader would use, or empty when there is none.
std::string find_openxr_runtime_manifest();

/// The backend serving the controller of `options.hand` (kNotBuilt when
/// compiled without OpenXR).
std::unique_ptr<Backend> make_openxr_backend(OpenXrOptions options = {});

}  // namespace sculpt::hal
