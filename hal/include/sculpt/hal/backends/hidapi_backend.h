#pragma once
// hidapi (hidraw flavour): reads input reports from /dev/hidraw*. Lists the
// known 3Dconnexion devices and any multi-axis controller (usage page 1,
// usage 8); takes the report descriptor from sysfs. Built when
// SCULPT_WITH_HIDAPI is on and hidapi-hidraw is found; otherwise the backend
// exists and reports kNotBuilt.

#include <memory>

#include "sculpt/hal/types/device.h"

namespace sculpt::hal {

std::unique_ptr<Backend> make_hidapi_backend();

}  // namespace sculpt::hal
