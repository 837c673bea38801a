// The udev rules file must cover exactly the devices the quirks table knows
// (a device added to the table but not to the rules would need root), and
// must never make a node world-writable.

#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "sculpt/hal/types/quirks.h"

namespace sculpt::hal {
namespace {

std::string rules_text() {
  std::ifstream in(std::string(SCULPT_TEST_DATA_DIR) +
                   "/../../hal/udev/70-sculpt-3dconnexion.rules");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(UdevRules, CoverTheQuirksTableOnBothNodeKindsAndNothingWorldWritable) {
  const std::string text = rules_text();
  ASSERT_FALSE(text.empty()) << "hal/udev/70-sculpt-3dconnexion.rules not found";
  std::set<std::string> hidraw, usb;
  const std::regex rule(
      R"re((ATTRS?)\{idVendor\}=="([0-9a-f]{4})", ATTRS?\{idProduct\}=="([0-9a-f]{4})", TAG\+="uaccess")re");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), rule); it != std::sregex_iterator();
       ++it) {
    ((*it)[1] == "ATTRS" ? hidraw : usb).insert((*it)[2].str() + ":" + (*it)[3].str());
  }
  std::set<std::string> want;
  for (const DeviceQuirks& q : all_quirks()) {
    if (q.kind != QuirkKind::kSpaceMouse) continue;
    char id[16];
    std::snprintf(id, sizeof id, "%04x:%04x", q.vendor_id, q.product_id);
    want.insert(id);
  }
  EXPECT_EQ(hidraw, want);
  EXPECT_EQ(usb, want);
  EXPECT_EQ(text.find("0666"), std::string::npos);
  EXPECT_EQ(text.find("MODE"), std::string::npos);
}

}  // namespace
}  // namespace sculpt::hal
