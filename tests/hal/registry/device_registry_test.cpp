// The whole live path without hardware: a byte-level fake transport
// (FeedBackend) feeding SpaceNavigator reports through the registry, the
// reader thread, the real parser and normaliser, the ring, the integrator and
// the stroke sampler, including a device that vanishes mid-stroke and comes back.

#include "sculpt/hal/registry/device_registry.h"

#include <chrono>
#include <thread>

#include <gtest/gtest.h>

#include "../parsers/report_bytes.h"
#include "plug_in_and_out.h"
#include "sculpt/hal/backends/feed_backend.h"
#include "sculpt/hal/pose/pose_integrator.h"
#include "sculpt/hal/stroke/stroke_sampler.h"

namespace sculpt::hal {
namespace {

using test::axes_report;

DeviceInfo navigator(const std::string& path, const std::string& location) {
  DeviceInfo info;
  info.path = path;
  info.name = "SpaceNavigator";
  info.vendor_id = 0x046d;
  info.product_id = 0xc626;
  info.usb_location = location;
  return info;
}

NormalizerConfig direct() {
  NormalizerConfig c;
  c.deadzone.fill(0.0f);
  c.curve = CurveKind::kLinear;
  c.filter = false;
  return c;
}

// Polls until `done` holds for the accumulated frames (bounded: a hang fails
// the test instead of blocking CI).
template <class Pred>
InputFrame poll_until(DeviceRegistry& r, Pred done) {
  InputFrame all;
  for (int i = 0; i < 5000; ++i) {
    InputFrame f;
    r.poll(f, 0);
    all.events.insert(all.events.end(), f.events.begin(), f.events.end());
    if (done(all)) return all;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ADD_FAILURE() << "timed out waiting for input";
  return all;
}

std::vector<InputEvent> motion_of(const InputFrame& f) {
  std::vector<InputEvent> motion;
  for (const InputEvent& e : f.events) {
    if (e.kind == InputKind::kMotion) motion.push_back(e);
  }
  return motion;
}

bool has(const InputFrame& f, InputKind kind) {
  for (const InputEvent& e : f.events) {
    if (e.kind == kind) return true;
  }
  return false;
}

struct Rig {
  FeedBackend* hid = nullptr;
  FeedBackend* usb = nullptr;
  std::unique_ptr<DeviceRegistry> registry;
};

Rig make_rig() {
  auto hid = std::make_unique<FeedBackend>("fake-hid");
  auto usb = std::make_unique<FeedBackend>("fake-usb");
  Rig rig{hid.get(), usb.get(), nullptr};
  std::vector<std::unique_ptr<Backend>> backends;
  backends.push_back(std::move(hid));
  backends.push_back(std::move(usb));
  rig.registry = std::make_unique<DeviceRegistry>(std::move(backends), direct());
  return rig;
}

TEST(DeviceRegistry, OpensEachPhysicalDeviceOnceThroughTheBestBackend) {
  Rig rig = make_rig();
  rig.hid->attach(navigator("hidraw0", "1-2"));
  rig.usb->attach(navigator("1-2:0", "1-2"));  // the same device seen through a second transport
  rig.usb->attach(navigator("1-3:0", "1-3"));  // another device only the second one sees
  ScanReport s = rig.registry->scan();
  EXPECT_TRUE(s.errors.empty());
  ASSERT_EQ(s.opened.size(), 2u);
  EXPECT_EQ(rig.registry->reader(s.opened[0])->info().backend, "fake-hid");
  EXPECT_EQ(rig.registry->reader(s.opened[1])->info().path, "1-3:0");
  // Scanning again opens nothing more.
  EXPECT_TRUE(rig.registry->scan().opened.empty());
  EXPECT_EQ(rig.registry->open_count(), 2u);
}

TEST(DeviceRegistry, IgnoredIdsAreNeverOpened) {
  Rig rig = make_rig();
  DeviceInfo cadmouse = navigator("hidraw1", "1-5");
  cadmouse.product_id = 0xc650;
  rig.hid->attach(cadmouse);
  DeviceInfo receiver_mouse = navigator("hidraw2", "1-6");
  receiver_mouse.product_id = 0xc652;
  receiver_mouse.usage_page = 1;
  receiver_mouse.usage = 2;
  rig.hid->attach(receiver_mouse);
  EXPECT_TRUE(rig.registry->scan().opened.empty());
}

TEST(DeviceRegistry, SpacenavdOwnsItsDeviceOverRawTransports) {
  auto spnav = std::make_unique<FeedBackend>("spnav");
  auto hid = std::make_unique<FeedBackend>("fake-hid");
  spnav->attach(navigator("spnav", ""));  // the daemon names no USB location
  hid->attach(navigator("hidraw0", "1-2"));
  std::vector<std::unique_ptr<Backend>> backends;
  backends.push_back(std::move(spnav));
  backends.push_back(std::move(hid));
  DeviceRegistry registry(std::move(backends), direct());
  const ScanReport s = registry.scan();
  ASSERT_EQ(s.opened.size(), 1u);
  EXPECT_EQ(registry.reader(s.opened[0])->info().backend, "spnav");
}

TEST(DeviceRegistry, StrokeSurvivesUnplugAndReplug) {
  Rig rig = make_rig();
  auto feed = rig.hid->attach(navigator("hidraw0", "1-2"));
  ASSERT_EQ(rig.registry->scan().opened.size(), 1u);

  PoseIntegratorConfig pc;
  pc.max_speed = 101.0f;
  PoseIntegrator integrator(pc);
  StrokeSampler sampler(4.0f, 0.5f);  // a dab every 2 units
  std::vector<Dab> dabs;

  // Button 0 down with the cap at rest starts the stroke at t = 0.
  feed->push(test::report_at(0, {3, 0x01, 0x00}));
  feed->push(test::report_at(0, axes_report(1, {0, 0, 0})));
  feed->push(test::report_at(0, axes_report(2, {0, 0, 0})));
  InputFrame start =
      poll_until(*rig.registry, [](const InputFrame& f) { return has(f, InputKind::kMotion); });
  ASSERT_TRUE(has(start, InputKind::kButton));
  sampler.begin(integrator.update(motion_of(start).back()), dabs);

  // 100 ms of full right push at 1 kHz, then the cable is pulled mid-stroke.
  for (int64_t i = 1; i <= 100; ++i) {
    const int64_t t = i * 1'000'000;
    feed->push(test::report_at(t, axes_report(1, {350, 0, 0})));
    feed->push(test::report_at(t, axes_report(2, {0, 0, 0})));
  }
  ASSERT_TRUE(feed->wait_drained(5000));
  rig.hid->detach("hidraw0", 100'000'001);

  // The main loop: every motion sample and event in order (the integrator
  // holds each deflection back to the previous sample's time).
  int64_t last_motion_t = 0;
  bool stroke_closed_on_disconnect = false;
  InputFrame all = poll_until(*rig.registry,
                              [](const InputFrame& f) { return has(f, InputKind::kDisconnected); });
  for (const InputEvent& m : motion_of(all)) {
    EXPECT_GT(m.t_ns, last_motion_t) << "motion must arrive in time order";
    last_motion_t = m.t_ns;
  }
  for (const InputEvent& m : motion_of(all))
    sampler.add(integrator.update(m), dabs);
  for (const InputEvent& e : all.events) {
    if (e.kind == InputKind::kDisconnected) {
      sampler.end();
      stroke_closed_on_disconnect = true;
      EXPECT_EQ(e.t_ns, 100'000'001) << "removal carries the transport's time";
    }
  }
  EXPECT_TRUE(has(start, InputKind::kConnected));
  EXPECT_TRUE(stroke_closed_on_disconnect);
  EXPECT_FALSE(sampler.active());
  EXPECT_EQ(last_motion_t, 100'000'000) << "the newest sample is never lost";
  // From rest at 0 to full at 1 ms (trapezoid: 0.5 ms), then 99 ms at full:
  // every coalesced sample's motion is kept.
  EXPECT_NEAR(integrator.pose().position.x, 99.5e-3 * 101.0, 1e-3);
  EXPECT_EQ(dabs.size(), 6u) << "dabs at 0, 2, 4, 6, 8, 10";
  EXPECT_EQ(rig.registry->open_count(), 0u) << "the vanished reader is retired";

  // Plugged back into the same port: the next scan picks it up.
  auto again = rig.hid->attach(navigator("hidraw0", "1-2"));
  ASSERT_EQ(rig.registry->scan().opened.size(), 1u);
  again->push(test::report_at(200'000'000, axes_report(1, {0, 175, 0})));
  again->push(test::report_at(200'000'000, axes_report(2, {0, 0, 0})));
  InputFrame back =
      poll_until(*rig.registry, [](const InputFrame& f) { return has(f, InputKind::kMotion); });
  EXPECT_TRUE(has(back, InputKind::kConnected));
  ASSERT_EQ(motion_of(back).size(), 1u);
  EXPECT_FLOAT_EQ(motion_of(back)[0].axes[kTz], 0.5f);
}

}  // namespace
}  // namespace sculpt::hal

namespace sculpt::hal {
namespace {

// Ids are never reused, so after many re-plugs the device open now has an
// id past any small range (the station's hub looked for it among ids 0-63,
// and past 64 opens no longer saw which device was there).
TEST(DeviceRegistry, TheFirstDeviceIsFoundWhateverItsId) {
  Rig rig = make_rig();
  EXPECT_FALSE(rig.registry->first_device().has_value());
  ASSERT_NO_FATAL_FAILURE(
      ::sculpt::test::plug_in_and_out(*rig.hid, *rig.registry, navigator("hidraw0", "1-2"), 70));
  EXPECT_FALSE(rig.registry->first_device().has_value());
  auto feed = rig.hid->attach(navigator("hidraw0", "1-2"));
  const ScanReport opened = rig.registry->scan();
  ASSERT_EQ(opened.opened.size(), 1u);
  EXPECT_GE(opened.opened[0], 70u);
  ASSERT_TRUE(rig.registry->first_device().has_value());
  EXPECT_EQ(*rig.registry->first_device(), opened.opened[0]);
  ASSERT_NE(rig.registry->reader(opened.opened[0]), nullptr);
  EXPECT_EQ(rig.registry->reader(opened.opened[0])->info().name, "SpaceNavigator");
  // A second one plugged in beside it: the first stays first.
  auto other = rig.usb->attach(navigator("libusb:1-3", "1-3"));
  ASSERT_EQ(rig.registry->scan().opened.size(), 1u);
  EXPECT_EQ(*rig.registry->first_device(), opened.opened[0]);
}

TEST(DeviceRegistry, OpenDeviceByIdBackendOrVendorProduct) {
  Rig rig = make_rig();
  rig.hid->attach(navigator("hidraw0", "1-2"));
  DeviceInfo compact = navigator("1-3:0", "1-3");
  compact.product_id = 0xc635;
  compact.vendor_id = 0x256f;
  rig.usb->attach(compact);

  auto by_vp = rig.registry->open_device("256F:C635");
  ASSERT_TRUE(by_vp.ok()) << by_vp.error().message();
  EXPECT_EQ(rig.registry->reader(*by_vp)->info().path, "1-3:0");
  auto by_id = rig.registry->open_device("fake-usb:1-3:0");
  ASSERT_TRUE(by_id.ok());
  EXPECT_EQ(*by_id, *by_vp) << "an open device is not opened twice";
  auto by_backend = rig.registry->open_device("fake-hid");
  ASSERT_TRUE(by_backend.ok());
  EXPECT_EQ(rig.registry->open_count(), 2u);

  const auto unknown = rig.registry->open_device("bluetooth:1");
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error().message(),
            "--device bluetooth:1: unknown backend 'bluetooth' (have fake-hid, fake-usb, or give "
            "vvvv:pppp)");
  const auto missing = rig.registry->open_device("fake-hid:hidraw9");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message().find("not found"), std::string::npos);
}

}  // namespace
}  // namespace sculpt::hal

namespace sculpt::hal {
namespace {

TEST(DeviceRegistry, NodeWithoutPermissionGivesTheUdevHint) {
  Rig rig = make_rig();
  DeviceInfo locked = navigator("hidraw0", "1-2");
  locked.accessible = false;
  rig.hid->attach(locked);
  const ScanReport s = rig.registry->scan();
  EXPECT_TRUE(s.opened.empty());
  ASSERT_EQ(s.errors.size(), 1u);
  EXPECT_EQ(
      s.errors[0],
      "fake-hid:hidraw0 (046d:c626): no permission; install the udev rules (see docs/devices.md)");
  const auto direct_open = rig.registry->open_device("fake-hid:hidraw0");
  ASSERT_FALSE(direct_open.ok());
  EXPECT_NE(direct_open.error().message().find("udev rules"), std::string::npos);
}

}  // namespace
}  // namespace sculpt::hal
