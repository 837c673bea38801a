// The firmware upload as a state machine through the scripted fake: the
// exact requests and bytes of a good attempt, the steps one by one, the
// quirks of the answers (split, leading zero, XOFF), failures named by step,
// retries that succeed later, giving up after the limit, and detecting a
// firmware that already runs.

#include "backends/falcon/falcon_firmware.h"

#include <cstdio>
#include <string>

#include <unistd.h>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "fake_falcon.h"
#include "fake_ftdi_transport.h"

namespace sculpt::hal::falcon {
namespace {

using testing::ControlRecord;
using testing::FakeFalcon;
using testing::FakeFtdiTransport;

std::vector<uint8_t> image(size_t n) {
  std::vector<uint8_t> v(n);
  for (size_t i = 0; i < n; ++i)
    v[i] = static_cast<uint8_t>(i * 7 + 3);
  return v;
}

FirmwareOptions quick() {
  FirmwareOptions o;
  o.handshake_tries = 5;
  o.reads_per_answer = 3;
  return o;
}

TEST(FalconFirmware, AGoodAttemptSendsLibnifalconsSequence) {
  FakeFtdiTransport fake;
  FakeFalcon falcon;
  falcon.attach(fake);
  const std::vector<uint8_t> fw = image(200);
  FirmwareReport report;
  const Status s = load_falcon_firmware(fake, fw, quick(), &report);
  ASSERT_TRUE(s.ok()) << s.error().message();
  EXPECT_EQ(report.attempts, 1);
  const std::vector<ControlRecord> expected = {
      // set-up: purge, latency 16 ms, 9600 8N1, no flow control, RTS low, DTR low, DTR high
      {FtdiRequest::kReset, 1, 0},
      {FtdiRequest::kReset, 2, 0},
      {FtdiRequest::kLatencyTimer, 16, 0},
      {FtdiRequest::kBaudRate, 0x4138, 0},
      {FtdiRequest::kLineProperties, 8, 0},
      {FtdiRequest::kFlowControl, 0, 0},
      {FtdiRequest::kModemControl, 0x0200, 0},
      {FtdiRequest::kModemControl, 0x0100, 0},
      {FtdiRequest::kModemControl, 0x0101, 0},
      // bootloader: DTR low, divisor 21
      {FtdiRequest::kModemControl, 0x0100, 0},
      {FtdiRequest::kBaudRate, 0x0015, 0},
      // run mode: latency 1 ms, 1.5 Mbaud, purge
      {FtdiRequest::kLatencyTimer, 1, 0},
      {FtdiRequest::kBaudRate, 0x0002, 0},
      {FtdiRequest::kReset, 1, 0},
      {FtdiRequest::kReset, 2, 0},
  };
  EXPECT_EQ(fake.controls, expected);
  ASSERT_EQ(fake.writes.size(), 6u);  // handshake, 'A', 62 + 62 + 62 + 14
  EXPECT_EQ(fake.writes[0], (std::vector<uint8_t>{0x0a, 0x43, 0x0d}));
  EXPECT_EQ(fake.writes[1], (std::vector<uint8_t>{0x41}));
  std::vector<uint8_t> sent;
  for (size_t i = 2; i < fake.writes.size(); ++i) {
    EXPECT_LE(fake.writes[i].size(), 62u);
    sent.insert(sent.end(), fake.writes[i].begin(), fake.writes[i].end());
  }
  EXPECT_EQ(sent, fw);
}

TEST(FalconFirmware, StepsOneAtATime) {
  FakeFtdiTransport fake;
  FakeFalcon falcon;
  falcon.attach(fake);
  const std::vector<uint8_t> fw = image(130);
  FirmwareUpload upload(fake, fw, quick());
  EXPECT_EQ(upload.step(), FirmwareStep::kSetUp);
  EXPECT_EQ(upload.advance(), FirmwareStep::kHandshake);
  EXPECT_TRUE(fake.writes.empty());
  EXPECT_EQ(upload.advance(), FirmwareStep::kBootBaud);
  EXPECT_EQ(upload.advance(), FirmwareStep::kSync);
  EXPECT_EQ(upload.advance(), FirmwareStep::kUpload);
  EXPECT_EQ(upload.advance(), FirmwareStep::kUpload);
  EXPECT_EQ(upload.uploaded_bytes(), 62u);
  EXPECT_EQ(upload.advance(), FirmwareStep::kUpload);
  EXPECT_EQ(upload.advance(), FirmwareStep::kRunMode);
  EXPECT_EQ(upload.uploaded_bytes(), 130u);
  EXPECT_EQ(upload.advance(), FirmwareStep::kDone);
  EXPECT_EQ(upload.advance(), FirmwareStep::kDone);
  EXPECT_TRUE(upload.error().empty());
}

TEST(FalconFirmware, HandshakeAnswersSplitOrWithALeadingZeroAreAccepted) {
  for (int variant = 0; variant < 3; ++variant) {
    FakeFtdiTransport fake;
    const std::vector<uint8_t> fw = image(10);
    int hellos = 0;
    fake.responder = [&, variant](std::span<const uint8_t> bytes, FakeFtdiTransport& t) {
      if (bytes.size() == 3) {
        if (variant == 0) {  // in two packets, an idle one between
          t.answer({0x0a, 0x44});
          t.answer_raw({0x31, 0x60});
          t.answer({0x2c, 0x0d});
        } else if (variant == 1) {  // libnifalcon's "Apple case"
          t.answer({0x00, 0x0a, 0x44, 0x2c, 0x0d});
        } else {  // garbage first, the right answer to the next try
          if (hellos++ == 0) {
            t.answer({0x7f, 0x7f, 0x7f, 0x7f});
          } else {
            t.answer({0x0a, 0x44, 0x2c, 0x0d});
          }
        }
      } else if (bytes.size() == 1) {
        t.answer({0x13, 0x41});  // XOFF before the echo (FalconCommFTD2XX.cpp)
      } else {
        t.answer(bytes);
      }
    };
    FirmwareUpload upload(fake, fw, quick());
    EXPECT_EQ(upload.run(), FirmwareStep::kDone) << variant << ": " << upload.error();
  }
}

TEST(FalconFirmware, AHandshakeNeverAnsweredFailsNamingTheStep) {
  FakeFtdiTransport fake;  // no responder: only idle status packets
  const std::vector<uint8_t> fw = image(10);
  FirmwareUpload upload(fake, fw, quick());
  EXPECT_EQ(upload.run(), FirmwareStep::kFailed);
  EXPECT_EQ(upload.error(),
            "handshake: no answer 0a 44 2c 0d to 0a 43 0d in 5 tries (last: nothing)");
  EXPECT_EQ(fake.writes.size(), 5u);
}

TEST(FalconFirmware, ABadEchoFailsTheAttemptAndALaterAttemptSucceeds) {
  FakeFtdiTransport fake;
  FakeFalcon falcon;
  falcon.corrupt_echo_attempts = {1, 2};
  falcon.silent_handshake_attempts = {3};
  falcon.attach(fake);
  const std::vector<uint8_t> fw = image(200);
  FirmwareReport report;
  const Status s = load_falcon_firmware(fake, fw, quick(), &report);
  ASSERT_TRUE(s.ok()) << s.error().message();
  EXPECT_EQ(report.attempts, 4);
  ASSERT_EQ(report.failures.size(), 3u);
  char want[96];
  std::snprintf(want, sizeof want, "upload: byte 70 echoed as %02x, sent %02x", fw[70] ^ 0x5a,
                fw[70]);
  EXPECT_EQ(report.failures[0], want);
  EXPECT_EQ(report.failures[1], want);
  EXPECT_EQ(report.failures[2].rfind("handshake: no answer", 0), 0u) << report.failures[2];
  EXPECT_EQ(falcon.uploaded, fw);
}

TEST(FalconFirmware, GivesUpAfterTheLimitWithTheLastError) {
  FakeFtdiTransport fake;
  FakeFalcon falcon;
  for (int i = 1; i <= 20; ++i)
    falcon.corrupt_echo_attempts.insert(i);
  falcon.corrupt_at = 3;
  falcon.attach(fake);
  const std::vector<uint8_t> fw = image(100);
  FirmwareReport report;
  const Status s = load_falcon_firmware(fake, fw, quick(), &report);  // default: 10 attempts
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(report.attempts, 10);
  EXPECT_EQ(falcon.attempt, 10);
  char want[160];
  std::snprintf(
      want, sizeof want,
      "Falcon firmware: gave up after 10 attempts; the last failed at upload: byte 3 echoed "
      "as %02x, sent %02x",
      fw[3] ^ 0x5a, fw[3]);
  EXPECT_EQ(s.error().message(), want);
}

TEST(FalconFirmware, ADeviceUnpluggedMidUploadIsNotRetried) {
  FakeFtdiTransport fake;
  FakeFalcon falcon;
  falcon.gone_during_upload_attempts = {1};
  falcon.attach(fake);
  const std::vector<uint8_t> fw = image(100);
  FirmwareReport report;
  const Status s = load_falcon_firmware(fake, fw, quick(), &report);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(report.attempts, 1);
  EXPECT_EQ(s.error().message(),
            "Falcon firmware: the device went away (upload: reading the echo: device gone)");
}

TEST(FalconFirmware, ARefusedControlRequestFailsTheSetUp) {
  FakeFtdiTransport fake;
  fake.control_status = UsbStatus::kError;
  const std::vector<uint8_t> fw = image(10);
  FirmwareUpload upload(fake, fw, quick());
  EXPECT_EQ(upload.run(), FirmwareStep::kFailed);
  EXPECT_EQ(upload.error(), "set-up: purge rx: transfer failed");
}

TEST(FalconFirmware, AnEmptyImageIsRefused) {
  FakeFtdiTransport fake;
  const Status s = load_falcon_firmware(fake, {}, quick());
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message().find("set-up: the firmware image is empty"), std::string::npos);
  EXPECT_TRUE(fake.controls.empty());
}

TEST(FalconFirmware, TheProbeTellsARunningFirmwareFromASilentDevice) {
  FakeFtdiTransport fake;
  FakeFalcon falcon;
  falcon.attach(fake);
  FirmwareProbe silent = probe_falcon_firmware(fake, 3, 2, 1);
  EXPECT_FALSE(silent.running);
  EXPECT_EQ(silent.status, UsbStatus::kOk);
  EXPECT_EQ(fake.writes.size(), 3u);
  EXPECT_EQ(fake.reads, 6);
  falcon.firmware_running = true;
  FirmwareProbe running = probe_falcon_firmware(fake, 3, 2, 1);
  EXPECT_TRUE(running.running);
  EXPECT_EQ(fake.writes.size(), 4u);  // the first answer was enough
  fake.gone = true;
  EXPECT_EQ(probe_falcon_firmware(fake, 3, 2, 1).status, UsbStatus::kNoDevice);
}

TEST(FalconFirmware, FirmwareFilesAreReadOrRefusedByName) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("sculpt-falcon-fw-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  const std::string missing = (dir / "sculpt-no-such-falcon-fw.bin").string();
  auto r = read_falcon_firmware_file(missing);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message(), missing + ": cannot open the Falcon firmware file");
  const std::string empty = (dir / "sculpt-empty-falcon-fw.bin").string();
  { std::ofstream(empty, std::ios::binary); }
  r = read_falcon_firmware_file(empty);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message(), empty + ": the Falcon firmware file is empty");
  const std::string good = (dir / "sculpt-good-falcon-fw.bin").string();
  { std::ofstream(good, std::ios::binary) << "\x01\x02\x03"; }
  r = read_falcon_firmware_file(good);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(*r, (std::vector<uint8_t>{1, 2, 3}));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace sculpt::hal::falcon
