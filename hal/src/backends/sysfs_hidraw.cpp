#include "backends/sysfs_hidraw.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>

namespace sculpt::hal::detail {
namespace {

std::string node_name(const std::string& dev_path) {
  return std::filesystem::path(dev_path).filename().string();
}

}  // namespace

std::vector<uint8_t> hidraw_report_descriptor(const std::string& dev_path) {
  std::ifstream in("/sys/class/hidraw/" + node_name(dev_path) + "/device/report_descriptor",
                   std::ios::binary);
  if (!in) return {};
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string hidraw_usb_location(const std::string& dev_path) {
  std::error_code ec;
  // .../usb1/1-4/1-4.2/1-4.2:1.0/0003:256F:C635.0004/hidraw/hidraw3: the
  // USB device is the last component shaped like "1-4.2".
  const auto real = std::filesystem::canonical("/sys/class/hidraw/" + node_name(dev_path), ec);
  if (ec) return {};
  static const std::regex kPort("^[0-9]+-[0-9]+(\\.[0-9]+)*$");
  std::string location;
  for (const auto& part : real) {
    const std::string s = part.string();
    if (std::regex_match(s, kPort)) location = s;
  }
  return location;
}

}  // namespace sculpt::hal::detail
