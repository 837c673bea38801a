#pragma once
// A backend that lists one network tracker it was told about and opens it
// only when asked: an OpenTrack listener or a VRPN server address is not
// plugged in and cannot be discovered, so there is nothing to enumerate
// beyond what the user named.

#include <functional>
#include <memory>
#include <string>

#include "sculpt/hal/types/device.h"

namespace sculpt::hal::detail {

using OpenTracker = std::function<Result<std::unique_ptr<Device>>()>;

/// `info.backend` is the backend's name; open() of another path is an error.
std::unique_ptr<Backend> make_tracker_listing_backend(DeviceInfo info, OpenTracker open);

}  // namespace sculpt::hal::detail
