#pragma once
// spnav: a libspnav client of a running spacenavd, which owns the device when
// it runs. Delivers kAxis x6 + kSync per motion event, kButton, and kRemoved
// when the daemon reports the device removed or closes the socket. Built when
// SCULPT_WITH_SPNAV is on and libspnav is found; else kNotBuilt. Without a
// daemon the status is kUnavailable ("spacenavd is not running").

#include <memory>

#include "sculpt/hal/types/device.h"

namespace sculpt::hal {

std::unique_ptr<Backend> make_spnav_backend();

}  // namespace sculpt::hal
