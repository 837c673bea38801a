#include "sculpt/hal/types/device_info.h"

#include <cstdio>

namespace sculpt::hal {

std::string DeviceInfo::vendor_product() const {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%04x:%04x", vendor_id, product_id);
  return buf;
}

std::string DeviceInfo::physical_key() const {
  // The location names the port, so two identical devices without serial
  // numbers stay apart; the serial is the fallback when it is unknown.
  if (!usb_location.empty()) return "usb@" + usb_location;
  return vendor_product() + ":" + (serial.empty() ? backend + ":" + path : serial);
}

}  // namespace sculpt::hal
