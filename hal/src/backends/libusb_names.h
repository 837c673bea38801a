#pragma once
// What libusb says about a device, in the words DeviceInfo uses: shared by
// the 3D-mouse backend (libusb_backend.cpp) and the Falcon's transport
// (falcon/libusb_ftdi_transport.cpp). Only with libusb.

#if SCULPT_HAL_HAVE_LIBUSB
#include <libusb.h>

#include <cstdint>
#include <string>

namespace sculpt::hal {

/// Where the device sits on the USB tree, "bus-port.port...": the same
/// physical device seen through another backend has the same location.
std::string usb_location(libusb_device* dev);

/// String descriptor `index` in ASCII; empty when there is none or it cannot
/// be read.
std::string usb_string_descriptor(libusb_device_handle* h, uint8_t index);

}  // namespace sculpt::hal
#endif
