#pragma once
// The description of one device as a backend sees it, before it is opened.

#include <cstdint>
#include <string>
#include <vector>

namespace sculpt::hal {

struct DeviceInfo {
  std::string backend;  ///< "hidapi", "libusb", "spnav", "sim", ...
  std::string path;     ///< backend-specific handle to open: "/dev/hidraw3", "usb:1-4:1.0", "spnav"
  std::string name;     ///< product string, or the quirks table's name when the device gives none
  std::string manufacturer;
  std::string serial;  ///< may be empty
  uint16_t vendor_id = 0;
  uint16_t product_id = 0;
  int interface_number = -1;  ///< USB interface, -1 when unknown
  uint16_t usage_page = 0;    ///< top-level HID usage page, 0 when unknown
  uint16_t usage = 0;         ///< top-level HID usage (page 1 usage 8 = multi-axis controller)
  /// Where the device sits on the USB tree ("1-4.2"), empty when unknown: the
  /// same physical device seen through two backends has the same location.
  std::string usb_location;
  /// The HID report descriptor when the backend can read it without opening
  /// the device (hidraw exposes it in sysfs); otherwise filled at open().
  std::vector<uint8_t> report_descriptor;
  /// False when the device node exists but this user may not open it.
  bool accessible = true;

  /// "046d:c626"
  std::string vendor_product() const;
  /// "backend:path", the id `sculpt run --device` takes.
  std::string id() const { return backend + ":" + path; }
  /// Identifies the physical device across backends: the USB location when
  /// known, else vendor:product:serial.
  std::string physical_key() const;
};

}  // namespace sculpt::hal
