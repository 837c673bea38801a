#include "backends/libusb_names.h"

#if SCULPT_HAL_HAVE_LIBUSB
namespace sculpt::hal {

std::string usb_location(libusb_device* dev) {
  uint8_t ports[8];
  const int n = libusb_get_port_numbers(dev, ports, sizeof ports);
  std::string s = std::to_string(libusb_get_bus_number(dev));
  for (int i = 0; i < n; ++i) {
    s.push_back(i == 0 ? '-' : '.');
    s += std::to_string(ports[i]);
  }
  return s;
}

std::string usb_string_descriptor(libusb_device_handle* h, uint8_t index) {
  if (index == 0) return {};
  unsigned char buf[256];
  const int n = libusb_get_string_descriptor_ascii(h, index, buf, sizeof buf);
  return n > 0 ? std::string(reinterpret_cast<char*>(buf), static_cast<size_t>(n)) : std::string();
}

}  // namespace sculpt::hal
#endif
