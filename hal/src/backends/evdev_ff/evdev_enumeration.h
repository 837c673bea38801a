#pragma once
// Listing the evdev nodes that can be force devices, through an EvdevIo (so
// the tests can fake a directory of devices).
//
// A node is listed when its device declares EV_FF with FF_CONSTANT. Sysfs
// is asked first, so nodes without force feedback (keyboards, mice) are not
// even opened; a node whose sysfs says FF_CONSTANT but which this user may
// not open (EACCES) is listed with accessible = false and sysfs's name and
// vendor:product. Without sysfs each node is opened and asked.

#include <vector>

#include "evdev_io.h"
#include "sculpt/base/result.h"
#include "sculpt/hal/types/device_info.h"

namespace sculpt::hal::evdev_ff {

/// DeviceInfo::backend "evdev-ff", path "/dev/input/eventN". Leaves `io` closed.
Result<std::vector<DeviceInfo>> list_evdev_force_devices(EvdevIo& io);

}  // namespace sculpt::hal::evdev_ff
