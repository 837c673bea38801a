// FalconDevice through the scripted fake: opening (firmware running, loaded
// from the bytes given, or missing), homing before force, one exchange per
// tick, zero(), unplug and transfer faults, malformed answers.

#include "backends/falcon/falcon_device.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "fake_falcon.h"
#include "fake_ftdi_transport.h"

namespace sculpt::hal::falcon {
namespace {

using testing::FakeFalcon;
using testing::FakeFtdiTransport;

constexpr uint8_t kHomingBit = 0x01;

struct Rig {
  FakeFtdiTransport* fake = nullptr;  // owned by the device once open
  std::unique_ptr<FakeFtdiTransport> owned = std::make_unique<FakeFtdiTransport>();
  FakeFalcon falcon;

  Rig() {
    fake = owned.get();
    falcon.attach(*fake);
  }
  Result<std::unique_ptr<FalconDevice>> open(FalconOpenOptions options = {}) {
    options.probe_writes = 3;
    options.probe_reads_per_write = 2;
    options.firmware_options.handshake_tries = 3;
    DeviceInfo info;
    info.backend = "falcon";
    info.path = "1-4";
    info.vendor_id = 0x0403;
    info.product_id = 0xcb48;
    return FalconDevice::open(std::move(owned), info, options);
  }
  /// Sets the encoders to the counts of position_mm.
  void place(glm::dvec3 position_mm) {
    const glm::dvec3 c =
        glm::round(falcon_counts_from_angles(*falcon_joint_angles_rad(position_mm)));
    falcon.encoders = {static_cast<int16_t>(c.x), static_cast<int16_t>(c.y),
                       static_cast<int16_t>(c.z)};
  }
};

TEST(FalconDevice, OpensARunningFirmwareWithoutUploadingAndStartsHoming) {
  Rig rig;
  rig.falcon.firmware_running = true;
  auto dev = rig.open();
  ASSERT_TRUE(dev.ok()) << dev.error().message();
  EXPECT_FALSE((*dev)->loaded_firmware());
  // No DTR reset: that would have thrown the running firmware away.
  for (const auto& c : rig.fake->controls)
    EXPECT_NE(c.value, 0x0101);
  EXPECT_EQ((*dev)->info().backend, "falcon");
  EXPECT_EQ((*dev)->limits().max_force_n, 8.0f);

  rig.place(glm::dvec3(0.0));
  ForceDeviceState state;
  ASSERT_EQ((*dev)->read(state), ForceIo::kOk);
  EXPECT_FALSE(state.homed);
  ASSERT_EQ((*dev)->write(glm::vec3(0.0f, 0.0f, 5.0f)), ForceIo::kOk);
  // Not homed: zero torque whatever was asked, homing on, LED red.
  EXPECT_EQ(rig.falcon.motors.back(), (std::array<int16_t, 3>{0, 0, 0}));
  EXPECT_EQ(rig.falcon.flags.back(), kHomingBit | kFalconLedRed);
}

TEST(FalconDevice, OnceHomedItReadsThePositionAndWritesTheForce) {
  Rig rig;
  rig.falcon.firmware_running = true;
  auto dev = rig.open();
  ASSERT_TRUE(dev.ok()) << dev.error().message();
  const glm::dvec3 where(12.0, -7.0, 18.0);
  rig.place(where);
  rig.falcon.homed = 7;
  rig.falcon.buttons = 0b0101;
  ForceDeviceState state;
  ASSERT_EQ((*dev)->read(state), ForceIo::kOk);
  EXPECT_TRUE(state.homed);
  EXPECT_EQ(state.buttons, 0b0101u);
  EXPECT_LT(glm::length(glm::dvec3(state.position_mm) - where), 0.1);
  const size_t packets = rig.falcon.motors.size();
  const glm::vec3 force(2.0f, -1.0f, 3.0f);
  ASSERT_EQ((*dev)->write(force), ForceIo::kOk);
  ASSERT_EQ(rig.falcon.motors.size(), packets + 1);  // one packet per write
  const auto expected = falcon_motor_commands(glm::dvec3(state.position_mm), glm::dvec3(force), {});
  EXPECT_EQ(rig.falcon.motors.back(), expected);
  EXPECT_NE(expected, (std::array<int16_t, 3>{0, 0, 0}));
  EXPECT_EQ(rig.falcon.flags.back(), kHomingBit | kFalconLedGreen);
  // The next read takes that write's answer: no second packet sent.
  ASSERT_EQ((*dev)->read(state), ForceIo::kOk);
  EXPECT_EQ(rig.falcon.motors.size(), packets + 1);
}

TEST(FalconDevice, ZeroWritesAZeroTorquePacket) {
  Rig rig;
  rig.falcon.firmware_running = true;
  rig.falcon.homed = 7;
  auto dev = rig.open();
  ASSERT_TRUE(dev.ok());
  rig.place(glm::dvec3(0.0, 5.0, 0.0));
  ForceDeviceState state;
  ASSERT_EQ((*dev)->read(state), ForceIo::kOk);
  ASSERT_EQ((*dev)->write(glm::vec3(6.0f, 0.0f, 0.0f)), ForceIo::kOk);
  ASSERT_NE(rig.falcon.motors.back(), (std::array<int16_t, 3>{0, 0, 0}));
  const size_t before = rig.fake->writes.size();
  (*dev)->zero();
  ASSERT_EQ(rig.fake->writes.size(), before + 1);
  EXPECT_EQ(std::string(rig.fake->writes.back().begin(), rig.fake->writes.back().end()),
            "<AAAAAAAAAAAADA>");
  EXPECT_EQ(rig.falcon.motors.back(), (std::array<int16_t, 3>{0, 0, 0}));
}

TEST(FalconDevice, UnplugIsRemovedForGood) {
  Rig rig;
  rig.falcon.firmware_running = true;
  auto dev = rig.open();
  ASSERT_TRUE(dev.ok());
  ForceDeviceState state;
  ASSERT_EQ((*dev)->read(state), ForceIo::kOk);
  rig.fake->gone = true;  // LIBUSB_ERROR_NO_DEVICE from now on
  EXPECT_EQ((*dev)->write(glm::vec3(1.0f)), ForceIo::kRemoved);
  EXPECT_EQ((*dev)->read(state), ForceIo::kRemoved);
  rig.fake->gone = false;  // even if the transport answered again
  EXPECT_EQ((*dev)->read(state), ForceIo::kRemoved);
  (*dev)->zero();  // harmless
}

TEST(FalconDevice, AnUnplugSeenOnTheReadSideIsRemovedToo) {
  Rig rig;
  rig.falcon.firmware_running = true;
  auto dev = rig.open();
  ASSERT_TRUE(dev.ok());
  ForceDeviceState state;
  ASSERT_EQ((*dev)->read(state), ForceIo::kOk);
  ASSERT_EQ((*dev)->write(glm::vec3(0.0f)), ForceIo::kOk);
  rig.fake->script.clear();
  rig.fake->answer_raw({}, UsbStatus::kNoDevice);
  EXPECT_EQ((*dev)->read(state), ForceIo::kRemoved);
  EXPECT_EQ((*dev)->write(glm::vec3(0.0f)), ForceIo::kRemoved);
}

TEST(FalconDevice, TransferErrorsAndBadAnswersAreFaultsAndCounted) {
  Rig rig;
  rig.falcon.firmware_running = true;
  rig.falcon.homed = 7;
  auto dev = rig.open();
  ASSERT_TRUE(dev.ok());
  FalconDevice& d = **dev;
  ForceDeviceState state;
  ASSERT_EQ(d.read(state), ForceIo::kOk);

  // A stalled pipe on the read.
  ASSERT_EQ(d.write(glm::vec3(0.0f)), ForceIo::kOk);
  rig.fake->script.clear();
  rig.fake->answer_raw({}, UsbStatus::kError);
  EXPECT_EQ(d.read(state), ForceIo::kFault);
  EXPECT_EQ(d.counters().transfer_errors, 1);

  // An answer cut short, then nothing.
  rig.fake->script.clear();
  rig.fake->responder = nullptr;
  ASSERT_EQ(d.write(glm::vec3(0.0f)), ForceIo::kOk);
  rig.fake->answer({'<', 'A', 'A', 'A'});
  EXPECT_EQ(d.read(state), ForceIo::kFault);
  EXPECT_EQ(d.counters().missing_answers, 1);
  EXPECT_EQ(d.counters().packets.short_reads, 1);

  // Garbage with a bad nibble.
  ASSERT_EQ(d.write(glm::vec3(0.0f)), ForceIo::kOk);
  const std::string bad = "<AAAAQAAAAAAAAA>";
  rig.fake->answer(std::vector<uint8_t>(bad.begin(), bad.end()));
  EXPECT_EQ(d.read(state), ForceIo::kFault);
  EXPECT_EQ(d.counters().packets.bad_nibble, 1);

  // The device answers again: back to normal.
  rig.falcon.attach(*rig.fake);
  EXPECT_EQ(d.read(state), ForceIo::kOk);
  EXPECT_TRUE(state.homed);

  // A write the device refuses.
  rig.fake->write_status = UsbStatus::kError;
  EXPECT_EQ(d.write(glm::vec3(1.0f)), ForceIo::kFault);
}

TEST(FalconDevice, WithoutFirmwareOrAFileItSaysWhatToGive) {
  Rig rig;  // a Falcon just powered up: nothing answers packets
  auto dev = rig.open();
  ASSERT_FALSE(dev.ok());
  EXPECT_EQ(
      dev.error().message(),
      "falcon:1-4: the Falcon's firmware is not loaded (it is lost at every power-up); give the "
      "Novint firmware file with --falcon-firmware FILE");
}

TEST(FalconDevice, LoadsTheFirmwareWhenNeededAndThenRuns) {
  Rig rig;
  rig.falcon.corrupt_echo_attempts = {1};  // the first upload fails, the second works
  FalconOpenOptions options;
  options.firmware.assign(150, 0x5a);
  auto dev = rig.open(options);
  ASSERT_TRUE(dev.ok()) << dev.error().message();
  EXPECT_TRUE((*dev)->loaded_firmware());
  EXPECT_EQ(rig.falcon.attempt, 2);
  EXPECT_EQ(rig.falcon.uploaded, options.firmware);
  ForceDeviceState state;
  EXPECT_EQ((*dev)->read(state), ForceIo::kOk);
}

TEST(FalconDevice, AFailedUploadNamesTheDeviceAndTheStep) {
  Rig rig;
  for (int i = 1; i <= 10; ++i)
    rig.falcon.silent_handshake_attempts.insert(i);
  FalconOpenOptions options;
  options.firmware.assign(20, 1);
  options.firmware_options.attempts = 2;
  auto dev = rig.open(options);
  ASSERT_FALSE(dev.ok());
  EXPECT_EQ(
      dev.error().message(),
      "falcon:1-4: Falcon firmware: gave up after 2 attempts; the last failed at handshake: no "
      "answer 0a 44 2c 0d to 0a 43 0d in 3 tries (last: 0a 45)");
}

TEST(FalconDevice, AnUnpluggedFalconFailsToOpen) {
  Rig rig;
  rig.fake->gone = true;
  auto dev = rig.open();
  ASSERT_FALSE(dev.ok());
  EXPECT_EQ(dev.error().message(), "falcon:1-4: resetting the bit mode: device gone");
}

}  // namespace
}  // namespace sculpt::hal::falcon
