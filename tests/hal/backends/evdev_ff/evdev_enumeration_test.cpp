// Listing through a fake directory of event nodes: only FF_CONSTANT
// devices, nodes without force feedback not even opened, a node this user
// may not open listed from sysfs as not accessible.

#include "backends/evdev_ff/evdev_enumeration.h"

#include <gtest/gtest.h>

#include "backends/evdev_ff/evdev_force_device.h"
#include "fake_evdev_io.h"
#include "sculpt/hal/backends/evdev_ff_backend.h"

namespace sculpt::hal::evdev_ff {
namespace {

using testing::FakeEvdevIo;
using testing::FakeEvdevNode;
using testing::FakeEvdevSystem;
using testing::Op;
using testing::sysfs_bitmap;

FakeEvdevNode device(std::set<uint16_t> ff, uint16_t vendor, uint16_t product, std::string name,
                     bool with_sysfs = true) {
  FakeEvdevNode n;
  n.ev_types = {EV_SYN, EV_KEY, EV_ABS};
  if (!ff.empty()) n.ev_types.insert(EV_FF);
  n.ff = ff;
  n.id = {BUS_USB, vendor, product, 1};
  n.name = name;
  if (with_sysfs) {
    EvdevSysfs s;
    s.name = name;
    s.vendor_id = vendor;
    s.product_id = product;
    s.ff_bitmap = sysfs_bitmap(ff);
    s.usb_location = "1-4";
    n.sysfs = s;
  }
  return n;
}

struct Directory {
  FakeEvdevSystem sys;
  Directory() {
    sys.nodes["/dev/input/event0"] = device({}, 0x046d, 0xc31c, "Keyboard");
    sys.nodes["/dev/input/event3"] = device({FF_RUMBLE, FF_PERIODIC}, 0x045e, 0x028e, "Pad");
    sys.nodes["/dev/input/event5"] = device({FF_CONSTANT, FF_GAIN}, 0x1234, 0x5678, "Stick");
    sys.nodes["/dev/input/event6"] = device({FF_CONSTANT}, 0x046d, 0xc294, "Wheel");
    sys.nodes["/dev/input/event6"].open_error = -EACCES;
    // No sysfs: opened and asked.
    sys.nodes["/dev/input/event8"] = device({FF_CONSTANT}, 0x0001, 0x0002, "Bare", false);
    // No sysfs and not ours: nothing says it has force feedback.
    sys.nodes["/dev/input/event9"] = device({}, 0x0003, 0x0004, "Unknown", false);
    sys.nodes["/dev/input/event9"].open_error = -EACCES;
  }
};

TEST(EvdevEnumeration, ListsTheNodesThatCanPlayAConstantForce) {
  Directory dir;
  FakeEvdevIo io(dir.sys);
  auto found = list_evdev_force_devices(io);
  ASSERT_TRUE(found.ok());
  ASSERT_EQ(found->size(), 3u);

  const DeviceInfo& stick = (*found)[0];
  EXPECT_EQ(stick.id(), "evdev-ff:/dev/input/event5");
  EXPECT_EQ(stick.name, "Stick");
  EXPECT_EQ(stick.vendor_product(), "1234:5678");
  EXPECT_EQ(stick.usb_location, "1-4");
  EXPECT_TRUE(stick.accessible);

  const DeviceInfo& wheel = (*found)[1];
  EXPECT_EQ(wheel.path, "/dev/input/event6");
  EXPECT_EQ(wheel.name, "Wheel") << "from sysfs: the node would not open";
  EXPECT_EQ(wheel.vendor_product(), "046d:c294");
  EXPECT_FALSE(wheel.accessible);

  EXPECT_EQ((*found)[2].path, "/dev/input/event8");
  EXPECT_EQ((*found)[2].name, "Bare");
}

TEST(EvdevEnumeration, OpensNoNodeWhoseSysfsShowsNoConstantForce) {
  Directory dir;
  FakeEvdevIo io(dir.sys);
  ASSERT_TRUE(list_evdev_force_devices(io).ok());
  for (const auto& c : dir.sys.calls_of(Op::kOpen)) {
    EXPECT_NE(c.node, "/dev/input/event0");
    EXPECT_NE(c.node, "/dev/input/event3");
  }
  size_t opened = 0;
  for (const auto& c : dir.sys.calls_of(Op::kOpen))
    opened += c.result == 0 ? 1 : 0;
  EXPECT_EQ(opened, 2u) << "event5 and event8";
  EXPECT_EQ(dir.sys.calls_of(Op::kClose).size(), opened) << "the listing leaves nothing open";
}

TEST(EvdevEnumeration, OpeningTheInaccessibleNodeSaysHowToGetAccess) {
  Directory dir;
  auto d = EvdevForceDevice::open(std::make_unique<FakeEvdevIo>(dir.sys), "/dev/input/event6");
  ASSERT_FALSE(d.ok());
  EXPECT_NE(d.error().message().find("input group"), std::string::npos);
  EXPECT_NE(d.error().message().find("TAG+=\"uaccess\""), std::string::npos);
}

TEST(EvdevSysfsBitmap, ReadsTheKernelsWordsMostSignificantFirst) {
  // FF_CONSTANT (82) and FF_GAIN (96) as a 64-bit kernel prints them ...
  EXPECT_TRUE(sysfs_bitmap_bit("100040000 0", FF_CONSTANT, 64));
  EXPECT_TRUE(sysfs_bitmap_bit("100040000 0", FF_GAIN, 64));
  EXPECT_FALSE(sysfs_bitmap_bit("100040000 0", FF_PERIODIC, 64));
  // ... and a 32-bit one.
  EXPECT_TRUE(sysfs_bitmap_bit("1 40000 0 0", FF_CONSTANT, 32));
  EXPECT_TRUE(sysfs_bitmap_bit("1 40000 0 0", FF_GAIN, 32));
  // No force feedback at all; garbage.
  EXPECT_FALSE(sysfs_bitmap_bit("0", FF_CONSTANT, 64));
  EXPECT_FALSE(sysfs_bitmap_bit("", FF_CONSTANT, 64));
  EXPECT_FALSE(sysfs_bitmap_bit("zz 40000 0", FF_CONSTANT, 32));
  // The fake's printer agrees with the reader on this machine.
  EXPECT_TRUE(sysfs_bitmap_bit(sysfs_bitmap({FF_CONSTANT, FF_GAIN}), FF_CONSTANT));
}

}  // namespace
}  // namespace sculpt::hal::evdev_ff

namespace sculpt::hal {
namespace {

// The real evdev edge, as far as a machine without input devices allows:
// listing works (finding nothing when /dev/input is absent) and opening a
// node that is not there names it.
TEST(EvdevFfBackend, ListsAndRefusesWithoutADevice) {
  EXPECT_EQ(evdev_ff_backend_status().state, BackendState::kReady);
  EXPECT_TRUE(list_evdev_force_devices().ok());
  auto d = open_evdev_force_device("/dev/input/event-not-there");
  ASSERT_FALSE(d.ok());
  EXPECT_NE(d.error().message().find("/dev/input/event-not-there"), std::string::npos);
}

}  // namespace
}  // namespace sculpt::hal
