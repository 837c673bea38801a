#pragma once
// Network trackers are not discovered: nothing is plugged in, and listening
// or connecting uninvited would let the network move the tool. The user
// names one (`--device opentrack:4242`, `--device vrpn:Tracker0@mocap`), and
// the caller adds its backend to the registry (add_backend) before listing
// or opening it.

#include <memory>
#include <string>
#include <string_view>

#include "sculpt/base/result.h"
#include "sculpt/hal/types/device.h"

namespace sculpt::hal {
class DeviceRegistry;
}

namespace sculpt::hal {

/// True for "opentrack", "opentrack:...", "vrpn:...", "openxr" and "openxr:..."
/// (an OpenXR controller is opened only when asked for too; valid or not: the
/// spec is meant for a tracker, and make_tracker_backend() says what is wrong).
bool names_tracker(std::string_view device_spec);

/// The backend of a tracker spec. listen_address: where an OpenTrack
/// listener binds (loopback unless the user asked for another). Errors name
/// the spec and what is wrong with it.
Result<std::unique_ptr<Backend>> make_tracker_backend(
    const std::string& device_spec, const std::string& listen_address = "127.0.0.1");

/// What `--device SPEC` needs before DeviceRegistry::open_device(): for a
/// tracker spec, adds its backend (last: it is never scanned for otherwise)
/// and returns the id that opens it; for any other spec, changes nothing and
/// returns the spec. Errors: a tracker spec that is wrong, named.
Result<std::string> add_named_tracker(DeviceRegistry& registry, const std::string& device_spec,
                                      const std::string& listen_address = "127.0.0.1");

}  // namespace sculpt::hal
