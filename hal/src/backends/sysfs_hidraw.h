#pragma once
// Linux sysfs lookups for a /dev/hidrawN node: its report descriptor and its
// place on the USB tree (so the registry can tell that hidapi and libusb see
// the same physical device).

#include <cstdint>
#include <string>
#include <vector>

namespace sculpt::hal::detail {

/// /sys/class/hidraw/hidrawN/device/report_descriptor; empty when unreadable.
std::vector<uint8_t> hidraw_report_descriptor(const std::string& dev_path);

/// The USB port path ("1-4.2") of the device behind /dev/hidrawN; empty when
/// it is not a USB device or sysfs is not there.
std::string hidraw_usb_location(const std::string& dev_path);

}  // namespace sculpt::hal::detail
