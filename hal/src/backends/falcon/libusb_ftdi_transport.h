#pragma once
// FtdiTransport over libusb-1.0, for a real Falcon (0403:cb48). Built only
// when SCULPT_HAL_HAVE_LIBUSB (falcon_backend.cpp says "not built" otherwise).
//
// Opening claims interface 0, detaching the kernel's ftdi_sio driver (which
// binds the Falcon as /dev/ttyUSB*) while open and re-attaching it on close.
// Control requests go as vendor OUT requests (0x40) to the device; bulk
// OUT 0x02, bulk IN 0x81 (64-byte packets, status bytes left in).

#include <memory>
#include <string>
#include <vector>

#include "ftdi_transport.h"
#include "sculpt/base/result.h"
#include "sculpt/hal/types/device_info.h"

namespace sculpt::hal::falcon {

/// The Falcons on the USB bus (backend "falcon", path = USB location).
Result<std::vector<DeviceInfo>> list_falcons_libusb();

/// Opens the Falcon at `path` (a list_falcons_libusb() path), or the first
/// one when `path` is empty; fills `info` with what was opened.
Result<std::unique_ptr<FtdiTransport>> open_falcon_libusb(const std::string& path,
                                                          DeviceInfo& info);

}  // namespace sculpt::hal::falcon
