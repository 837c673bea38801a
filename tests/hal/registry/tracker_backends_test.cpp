// Named trackers join the registry only when asked for, and then show in its
// listing (what `sculpt devices --device ...` prints) without being opened.

#include "sculpt/hal/registry/tracker_backends.h"

#include <gtest/gtest.h>

#include "sculpt/hal/registry/device_registry.h"

namespace sculpt::hal {
namespace {

TEST(TrackerBackends, TellsTrackerSpecsFromDeviceIds) {
  EXPECT_TRUE(names_tracker("opentrack"));
  EXPECT_TRUE(names_tracker("opentrack:4242"));
  EXPECT_TRUE(names_tracker("vrpn:Tracker0@localhost"));
  EXPECT_FALSE(names_tracker("hidapi:/dev/hidraw0"));
  EXPECT_FALSE(names_tracker("046d:c626"));
  EXPECT_FALSE(names_tracker("opentracker"));
}

TEST(TrackerBackends, MakesTheBackendASpecNames) {
  auto ot = make_tracker_backend("opentrack:5000");
  ASSERT_TRUE(ot.ok()) << ot.error().message();
  EXPECT_EQ((*ot)->name(), "opentrack");
  EXPECT_EQ((*ot)->enumerate()->front().id(), "opentrack:5000");
  auto vrpn = make_tracker_backend("vrpn:Tracker0@mocap.local");
  ASSERT_TRUE(vrpn.ok()) << vrpn.error().message();
  EXPECT_EQ((*vrpn)->enumerate()->front().id(), "vrpn:Tracker0@mocap.local:3883");
}

TEST(TrackerBackends, TheListenAddressReachesTheListener) {
  auto ot = make_tracker_backend("opentrack", "192.168.1.20");
  ASSERT_TRUE(ot.ok());
  EXPECT_NE((*ot)->enumerate()->front().name.find("192.168.1.20:4242"), std::string::npos);
}

TEST(TrackerBackends, BadSpecsSayWhatIsWrong) {
  auto port = make_tracker_backend("opentrack:99999");
  ASSERT_FALSE(port.ok());
  EXPECT_NE(port.error().message().find("99999"), std::string::npos);
  auto vrpn = make_tracker_backend("vrpn:nohost");
  ASSERT_FALSE(vrpn.ok());
  EXPECT_NE(vrpn.error().message().find("NAME@HOST"), std::string::npos);
  EXPECT_FALSE(make_tracker_backend("hidapi:/dev/hidraw0").ok());
}

TEST(TrackerBackends, AnAddedTrackerIsListedWithoutBeingOpened) {
  DeviceRegistry registry({});
  auto ot = make_tracker_backend("opentrack:4243");
  ASSERT_TRUE(ot.ok());
  registry.add_backend(std::move(ot).value());
  const auto listing = registry.list();
  ASSERT_EQ(listing.size(), 1u);
  EXPECT_EQ(listing[0].backend, "opentrack");
  EXPECT_EQ(listing[0].status.state, BackendState::kReady);
  ASSERT_EQ(listing[0].devices.size(), 1u);
  EXPECT_EQ(listing[0].devices[0].id(), "opentrack:4243");
  EXPECT_EQ(registry.open_count(), 0u);
}

TEST(TrackerBackends, AddNamedTrackerAddsOnlyWhatTheDeviceSpecNames) {
  DeviceRegistry registry({});
  auto other = add_named_tracker(registry, "hidapi:/dev/hidraw0");
  ASSERT_TRUE(other.ok());
  EXPECT_EQ(*other, "hidapi:/dev/hidraw0");
  EXPECT_TRUE(registry.list().empty()) << "a device id adds no tracker";
  auto id = add_named_tracker(registry, "vrpn:Tracker0@localhost");
  ASSERT_TRUE(id.ok()) << id.error().message();
  EXPECT_EQ(*id, "vrpn");
  const auto listing = registry.list();
  ASSERT_EQ(listing.size(), 1u);
  ASSERT_EQ(listing[0].devices.size(), 1u);
  EXPECT_EQ(registry.open_count(), 0u);
  auto bad = add_named_tracker(registry, "opentrack:99999");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().message().rfind("--device opentrack:99999: ", 0), 0u)
      << bad.error().message();
  EXPECT_EQ(registry.list().size(), 1u);
}

}  // namespace
}  // namespace sculpt::hal
