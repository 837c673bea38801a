#pragma once
// libusb: interrupt-IN transfers on the device's HID interface, detaching the
// kernel's usbhid driver while open and re-attaching it on close; hotplug
// through libusb's hotplug API where the platform has it. Lists only the
// known 3Dconnexion IDs (an unknown controller's usage needs its descriptor,
// which hidapi reads without opening the device). Built when
// SCULPT_WITH_LIBUSB is on and libusb-1.0 is found; else kNotBuilt.

#include <memory>

#include "sculpt/hal/types/device.h"

namespace sculpt::hal {

std::unique_ptr<Backend> make_libusb_backend();

}  // namespace sculpt::hal
