// The FTDI edge: the baud divisors the Falcon needs, the status bytes that
// open every IN packet, and the set-up requests' wire values.

#include "backends/falcon/ftdi_transport.h"

#include <gtest/gtest.h>

#include "fake_ftdi_transport.h"

namespace sculpt::hal::falcon {
namespace {

using testing::ControlRecord;
using testing::FakeFtdiTransport;

void expect_divisor(uint32_t baud, uint16_t value, uint16_t index, uint32_t actual) {
  auto d = ftdi_baud_divisor(baud);
  ASSERT_TRUE(d.ok()) << baud << ": " << d.error().message();
  EXPECT_EQ(d->value, value) << baud;
  EXPECT_EQ(d->index, index) << baud;
  EXPECT_EQ(d->actual_baud, actual) << baud;
}

TEST(FtdiBaudDivisor, TheFalconsRatesGiveTheValuesItIsKnownToTake) {
  // The handshake at 9600: 3 MHz / 312.5, the 0x4138 libnifalcon sends.
  expect_divisor(9600, 0x4138, 0, 9600);
  // The bootloader: divisor 21 exactly (libnifalcon's libusb layer sends 0x15).
  expect_divisor(142857, 0x0015, 0, 142857);
  // 140000 (its libftdi and FTD2XX layers) is 21 3/8: code 4, the third bit in wIndex.
  expect_divisor(140000, 0x0015, 1, 140350);
  // Run mode: divisor 2 (1.5 Mbaud), also for the 1456312 the other layers ask.
  expect_divisor(1'500'000, 0x0002, 0, 1'500'000);
  expect_divisor(1'456'312, 0x0002, 0, 1'500'000);
}

TEST(FtdiBaudDivisor, SpecialDivisorsFractionsAndLimits) {
  expect_divisor(3'000'000, 0x0000, 0, 3'000'000);  // divisor 1 is encoded 0
  expect_divisor(2'000'000, 0x0001, 0, 2'000'000);  // divisor 1.5 is encoded 1
  expect_divisor(115200, 0x001a, 0, 115384);        // 26.04 -> 26
  expect_divisor(38400, 0xc04e, 0, 38400);          // 78.125 = 78 1/8: code 3 -> bits 14-15
  expect_divisor(57600, 0xc034, 0, 57553);          // 52.08 -> 52 1/8
  expect_divisor(300, 0x2710, 0, 300);              // 10000
  EXPECT_FALSE(ftdi_baud_divisor(0).ok());
  EXPECT_FALSE(ftdi_baud_divisor(100).ok());        // below 3 MHz / 16383.875
  EXPECT_FALSE(ftdi_baud_divisor(2'500'000).ok());  // between 2 and 3 Mbaud: 20 % off either
  EXPECT_FALSE(ftdi_baud_divisor(6'000'000).ok());
}

TEST(FtdiStatusBytes, EveryPacketLosesItsTwoStatusBytes) {
  std::vector<uint8_t> raw;
  for (int packet = 0; packet < 2; ++packet) {
    raw.push_back(0x31);
    raw.push_back(0x60);
    for (int i = 0; i < 62; ++i)
      raw.push_back(static_cast<uint8_t>(packet * 62 + i));
  }
  // A short packet ends a USB transfer: it can only come last.
  raw.insert(raw.end(), {0x31, 0x60, 0xaa, 0xbb});
  std::vector<uint8_t> out;
  strip_ftdi_status(raw, out);
  ASSERT_EQ(out.size(), 126u);
  for (size_t i = 0; i < 124; ++i)
    EXPECT_EQ(out[i], i) << i;
  EXPECT_EQ(out[124], 0xaa);
  EXPECT_EQ(out[125], 0xbb);
  out.clear();
  strip_ftdi_status(std::vector<uint8_t>{0x31, 0x60}, out);  // an idle chip's packet
  EXPECT_TRUE(out.empty());
  strip_ftdi_status(std::vector<uint8_t>{0x31}, out);
  EXPECT_TRUE(out.empty());
}

TEST(FtdiReader, GathersSplitAnswersAndKeepsWhatIsNotTaken) {
  FakeFtdiTransport fake;
  fake.answer_raw({0x31, 0x60});  // idle
  fake.answer({0x0a, 0x44});
  fake.answer_raw({0x31, 0x60, 0x2c, 0x0d, 0x99}, UsbStatus::kTimeout);  // partial transfer
  FtdiReader reader(fake);
  EXPECT_EQ(reader.read_at_least(4, 8, 10), UsbStatus::kOk);
  EXPECT_EQ(fake.reads, 3);
  EXPECT_EQ(reader.pending(), (std::vector<uint8_t>{0x0a, 0x44, 0x2c, 0x0d, 0x99}));
  reader.consume(4);
  EXPECT_EQ(reader.pending(), (std::vector<uint8_t>{0x99}));
  EXPECT_EQ(reader.read_at_least(3, 5, 10), UsbStatus::kTimeout);
  EXPECT_EQ(fake.reads, 8);
  fake.gone = true;
  EXPECT_EQ(reader.read_at_least(3, 5, 10), UsbStatus::kNoDevice);
}

TEST(FtdiRequests, WireValues) {
  FakeFtdiTransport fake;
  EXPECT_EQ(ftdi_reset(fake, FtdiReset::kPurgeRx), UsbStatus::kOk);
  EXPECT_EQ(ftdi_reset(fake, FtdiReset::kPurgeTx), UsbStatus::kOk);
  EXPECT_EQ(ftdi_set_latency_timer_ms(fake, 16), UsbStatus::kOk);
  EXPECT_EQ(ftdi_set_baud(fake, 9600), UsbStatus::kOk);
  EXPECT_EQ(ftdi_set_line_8n1(fake), UsbStatus::kOk);
  EXPECT_EQ(ftdi_set_flow_control_off(fake), UsbStatus::kOk);
  EXPECT_EQ(ftdi_set_rts(fake, false), UsbStatus::kOk);
  EXPECT_EQ(ftdi_set_dtr(fake, true), UsbStatus::kOk);
  EXPECT_EQ(ftdi_set_bit_mode(fake, 0x01, 0xf0), UsbStatus::kOk);
  EXPECT_EQ(ftdi_set_baud(fake, 1), UsbStatus::kError);  // refused, nothing sent
  const std::vector<ControlRecord> expected = {
      {FtdiRequest::kReset, 1, 0},
      {FtdiRequest::kReset, 2, 0},
      {FtdiRequest::kLatencyTimer, 16, 0},
      {FtdiRequest::kBaudRate, 0x4138, 0},
      {FtdiRequest::kLineProperties, 8, 0},
      {FtdiRequest::kFlowControl, 0, 0},
      {FtdiRequest::kModemControl, 0x0200, 0},
      {FtdiRequest::kModemControl, 0x0101, 0},
      {FtdiRequest::kBitMode, 0x01f0, 0},
  };
  EXPECT_EQ(fake.controls, expected);
}

}  // namespace
}  // namespace sculpt::hal::falcon
