// The Novint SDK firmware's packet against bytes worked out by hand, and the
// stream reader against what a USB line delivers: splits, garbage, cuts.

#include "backends/falcon/falcon_packet.h"

#include <string>

#include <gtest/gtest.h>

namespace sculpt::hal::falcon {
namespace {

std::vector<uint8_t> bytes(const std::string& s) {
  return {s.begin(), s.end()};
}

TEST(FalconPacket, EncodesMotorsLedsAndHomingAsWorkedOutByHand) {
  FalconOutput out;
  // 1447 = 0x05a7: nibbles 7 a 5 0, least significant first -> H K F A.
  // -1447 = 0xfa59: 9 5 a f -> J F K P. Flags: green 0x02 | homing 0x01 -> 'D'.
  out.motor = {1447, -1447, 0};
  out.leds = kFalconLedGreen;
  out.homing = true;
  const FalconPacket p = encode_falcon_output(out);
  EXPECT_EQ(std::string(p.begin(), p.end()), "<HKFAJFKPAAAADA>");
  out = {};
  out.motor = {32767, -32768, -1};
  out.leds = kFalconLedRed | kFalconLedBlue;
  const FalconPacket q = encode_falcon_output(out);
  EXPECT_EQ(std::string(q.begin(), q.end()), "<PPPHAAAIPPPPMA>");
}

TEST(FalconPacket, DecodesEncodersButtonsAndHomedFlagsAsWorkedOutByHand) {
  // Byte 13 = 'A' + 0x75: buttons 5 (bits 0-3), homed 7 (bits 4-6).
  std::vector<uint8_t> p = bytes("<HKFAJFKPPPPP");
  p.push_back(static_cast<uint8_t>('A' + 0x75));
  p.push_back('Z');  // byte 14: not checked
  p.push_back('>');
  FalconInput in;
  ASSERT_EQ(decode_falcon_input(p, in), FalconPacketError::kNone);
  EXPECT_EQ(in.encoder[0], 1447);
  EXPECT_EQ(in.encoder[1], -1447);
  EXPECT_EQ(in.encoder[2], -1);
  EXPECT_EQ(in.buttons, 5);
  EXPECT_EQ(in.homed, 7);
  EXPECT_TRUE(in.all_homed());
  p[13] = static_cast<uint8_t>('A' + 0x30);  // two motors homed, no buttons
  ASSERT_EQ(decode_falcon_input(p, in), FalconPacketError::kNone);
  EXPECT_EQ(in.homed, 3);
  EXPECT_EQ(in.buttons, 0);
  EXPECT_FALSE(in.all_homed());
}

TEST(FalconPacket, MalformedPacketsAreRefusedAndLeaveTheInputAlone) {
  const std::vector<uint8_t> good = bytes("<AAAAAAAAAAAAAA>");
  FalconInput in;
  in.encoder = {7, 8, 9};
  EXPECT_EQ(decode_falcon_input(std::span(good).first(15), in), FalconPacketError::kShort);
  std::vector<uint8_t> p = good;
  p[0] = '[';
  EXPECT_EQ(decode_falcon_input(p, in), FalconPacketError::kFraming);
  p = good;
  p[15] = 'A';
  EXPECT_EQ(decode_falcon_input(p, in), FalconPacketError::kFraming);
  p = good;
  p[5] = 'Q';  // one past 'P'
  EXPECT_EQ(decode_falcon_input(p, in), FalconPacketError::kNibble);
  p[5] = '@';  // one before 'A'
  EXPECT_EQ(decode_falcon_input(p, in), FalconPacketError::kNibble);
  p = good;
  p[13] = static_cast<uint8_t>('A' + 0x80);
  EXPECT_EQ(decode_falcon_input(p, in), FalconPacketError::kNibble);
  EXPECT_EQ(in.encoder[0], 7);
}

TEST(FalconPacketReader, PacketsSplitAnyhowComeOutWhole) {
  std::string stream = "<HKFAJFKPPPPPAA><BAAAAAAAAAAAAA>";
  FalconPacketReader reader;
  int found = 0;
  for (char c : stream) {
    const uint8_t b = static_cast<uint8_t>(c);
    found += reader.feed(std::span(&b, 1));
  }
  EXPECT_EQ(found, 2);
  EXPECT_EQ(reader.newest().encoder[0], 1);
  EXPECT_EQ(reader.counters().packets, 2);
  EXPECT_EQ(reader.counters().bad_framing, 0);
  EXPECT_EQ(reader.partial(), 0u);
}

TEST(FalconPacketReader, GarbageAndCutPacketsAreCountedAndTheNextGoodOneFound) {
  FalconPacketReader reader;
  // Garbage, a packet cut after 7 bytes, then a good one.
  EXPECT_EQ(reader.feed(bytes("xyz<HKFAJF<CAAAAAAAAAAAAA>")), 1);
  EXPECT_EQ(reader.newest().encoder[0], 2);
  EXPECT_EQ(reader.counters().bad_framing, 2);
  EXPECT_EQ(reader.counters().skipped_bytes, 3 + 7);
  // A framed packet with a bad nibble is dropped, counted, and the next read.
  EXPECT_EQ(reader.feed(bytes("<AAAAQAAAAAAAAA><DAAAAAAAAAAAAA>")), 1);
  EXPECT_EQ(reader.counters().bad_nibble, 1);
  EXPECT_EQ(reader.newest().encoder[0], 3);
  // A '<' whose packet never ends in '>' at byte 15.
  EXPECT_EQ(reader.feed(bytes("<AAAAAAAAAAAAAAA<EAAAAAAAAAAAAA>")), 1);
  EXPECT_EQ(reader.newest().encoder[0], 4);
  EXPECT_EQ(reader.counters().packets, 3);
}

TEST(FalconPacketReader, HoldsAtMostOnePartialPacket) {
  FalconPacketReader reader;
  std::vector<uint8_t> noise(1000);
  for (size_t i = 0; i < noise.size(); ++i)
    noise[i] = static_cast<uint8_t>(i * 37 + (i % 3 == 0 ? '<' : 0));
  reader.feed(noise);
  EXPECT_LT(reader.partial(), kFalconPacketBytes);
  EXPECT_GT(reader.counters().bad_framing, 0);
  // Whatever the noise left, the next good packet comes through.
  EXPECT_EQ(reader.feed(bytes("<FAAAAAAAAAAAAA>")), 1);
  EXPECT_EQ(reader.newest().encoder[0], 5);
}

}  // namespace
}  // namespace sculpt::hal::falcon
