// The Falcon's udev rule must give the seat's user the USB device node of
// every force device in the limits table that is real hardware (else the
// station needs root to open it), and must not make it world-writable.

#include <cstdio>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "sculpt/hal/force/force_limits.h"

namespace sculpt::hal {
namespace {

TEST(FalconUdevRule, CoversTheForceDevicesUsbNodesAndNothingWorldWritable) {
  std::ifstream in(std::string(SCULPT_TEST_DATA_DIR) + "/../../hal/udev/71-sculpt-falcon.rules");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  ASSERT_FALSE(text.empty()) << "hal/udev/71-sculpt-falcon.rules not found";
  const std::regex rule(
      R"re(SUBSYSTEM=="usb", ENV\{DEVTYPE\}=="usb_device", ATTR\{idVendor\}=="([0-9a-f]{4})", ATTR\{idProduct\}=="([0-9a-f]{4})", TAG\+="uaccess")re");
  std::set<std::string> got;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), rule); it != std::sregex_iterator();
       ++it)
    got.insert((*it)[1].str() + ":" + (*it)[2].str());
  std::set<std::string> want;
  for (const ForceLimits& l : all_force_limits()) {
    if (l.vendor_id == 0) continue;  // the simulated arm
    char id[16];
    std::snprintf(id, sizeof id, "%04x:%04x", l.vendor_id, l.product_id);
    want.insert(id);
  }
  EXPECT_EQ(got, want);
  // Outside comments, no MODE= (a permission change would reach every user).
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] == '#') continue;
    EXPECT_EQ(line.find("MODE="), std::string::npos) << line;
  }
}

}  // namespace
}  // namespace sculpt::hal
