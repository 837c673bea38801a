// The real transports, as far as a machine without a device allows: each one
// is built (or says it is not), and enumeration either works (listing only
// 6-DOF devices, none ignored) or the backend says why it is unavailable.

#include <gtest/gtest.h>

#include "sculpt/hal/backends/hidapi_backend.h"
#include "sculpt/hal/backends/libusb_backend.h"
#include "sculpt/hal/backends/spnav_backend.h"
#include "sculpt/hal/types/quirks.h"

namespace sculpt::hal {
namespace {

void check_backend(Backend& b, std::string_view name) {
  EXPECT_EQ(b.name(), name);
  const BackendStatus st = b.status();
  auto devices = b.enumerate();
  switch (st.state) {
    case BackendState::kReady:
      ASSERT_TRUE(devices.ok()) << name << ": " << devices.error().message();
      for (const DeviceInfo& d : *devices) {
        EXPECT_EQ(d.backend, name);
        EXPECT_FALSE(d.path.empty());
        if (name != "spnav") {
          EXPECT_FALSE(is_ignored(d.vendor_id, d.product_id, d.usage_page, d.usage))
              << d.vendor_product();
        }
      }
      std::printf("[ info ] %s: enumeration works, %zu device(s)\n", std::string(name).c_str(),
                  devices->size());
      break;
    case BackendState::kNotBuilt:
    case BackendState::kUnavailable:
      EXPECT_FALSE(st.note.empty()) << name << " must say why it is not ready";
      EXPECT_FALSE(devices.ok());
      std::printf("[ info ] %s: %s\n", std::string(name).c_str(), st.note.c_str());
      break;
  }
}

TEST(HardwareBackends, HidapiEnumerates) {
  auto b = make_hidapi_backend();
#if SCULPT_TEST_EXPECT_HIDAPI
  EXPECT_NE(b->status().state, BackendState::kNotBuilt);
#endif
  check_backend(*b, "hidapi");
}

TEST(HardwareBackends, LibusbEnumerates) {
  auto b = make_libusb_backend();
  check_backend(*b, "libusb");
}

TEST(HardwareBackends, SpnavReportsTheDaemon) {
  auto b = make_spnav_backend();
  check_backend(*b, "spnav");
}

}  // namespace
}  // namespace sculpt::hal
