// Encoding and decoding of the Novint SDK firmware's packet. Every byte of it
// is printable: values go as nibbles offset by 'A', so '<' (0x3c) and '>'
// (0x3e), which are below 'A', never occur inside a packet and a reader out
// of step finds the next packet at the next '<'.

#include "falcon_packet.h"

#include <algorithm>

namespace sculpt::hal::falcon {
namespace {

constexpr uint8_t kStart = '<';
constexpr uint8_t kEnd = '>';
constexpr uint8_t kNibbleBase = 'A';
constexpr size_t kFlagsByte = 13;
constexpr size_t kSpareByte = 14;

}  // namespace

FalconPacket encode_falcon_output(const FalconOutput& out) {
  FalconPacket p;
  p.fill(kNibbleBase);
  p[0] = kStart;
  p[15] = kEnd;
  for (size_t m = 0; m < 3; ++m) {
    const auto v = static_cast<uint16_t>(out.motor[m]);
    for (size_t n = 0; n < 4; ++n)
      p[1 + 4 * m + n] = static_cast<uint8_t>(kNibbleBase + ((v >> (4 * n)) & 0xf));
  }
  // libnifalcon FalconFirmwareNovintSDK.cpp formatInput(): LEDs and homing
  // share byte 13; byte 14 is sent as a zero nibble.
  const uint8_t flags = static_cast<uint8_t>((out.leds & 0x0e) | (out.homing ? 0x01 : 0x00));
  p[kFlagsByte] = static_cast<uint8_t>(kNibbleBase + flags);
  p[kSpareByte] = kNibbleBase;
  return p;
}

FalconPacketError decode_falcon_input(std::span<const uint8_t> bytes, FalconInput& in) {
  if (bytes.size() < kFalconPacketBytes) return FalconPacketError::kShort;
  if (bytes[0] != kStart || bytes[15] != kEnd) return FalconPacketError::kFraming;
  FalconInput decoded;
  for (size_t m = 0; m < 3; ++m) {
    uint16_t v = 0;
    for (size_t n = 0; n < 4; ++n) {
      const uint8_t b = bytes[1 + 4 * m + n];
      if (b < kNibbleBase || b > kNibbleBase + 15) return FalconPacketError::kNibble;
      v = static_cast<uint16_t>(v | ((b - kNibbleBase) << (4 * n)));
    }
    decoded.encoder[m] = static_cast<int16_t>(v);
  }
  // Byte 13 is not a nibble on the way back: libnifalcon formatOutput()
  // takes the buttons from bits 0-3 and the homed flags from bits 4-6 of
  // (byte - 'A'), so it spans 'A'..'A'+127.
  const uint8_t f = bytes[kFlagsByte];
  if (f < kNibbleBase || f > kNibbleBase + 0x7f) return FalconPacketError::kNibble;
  decoded.buttons = static_cast<uint8_t>((f - kNibbleBase) & 0x0f);
  decoded.homed = static_cast<uint8_t>(((f - kNibbleBase) >> 4) & 0x07);
  in = decoded;
  return FalconPacketError::kNone;
}

int FalconPacketReader::feed(std::span<const uint8_t> bytes) {
  int found = 0;
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
  size_t at = 0;
  while (true) {
    // Out of step: skip to the next '<', counting one framing error per gap.
    const auto start =
        std::find(buffer_.begin() + static_cast<ptrdiff_t>(at), buffer_.end(), kStart);
    const size_t skip = static_cast<size_t>(start - buffer_.begin()) - at;
    if (skip > 0) {
      ++counters_.bad_framing;
      counters_.skipped_bytes += static_cast<int64_t>(skip);
      at += skip;
    }
    if (buffer_.size() - at < kFalconPacketBytes) break;
    const std::span<const uint8_t> candidate(buffer_.data() + at, kFalconPacketBytes);
    FalconInput in;
    switch (decode_falcon_input(candidate, in)) {
      case FalconPacketError::kNone:
        newest_ = in;
        ++counters_.packets;
        ++found;
        at += kFalconPacketBytes;
        break;
      case FalconPacketError::kNibble:
        // Framed but with a byte out of range: dropped whole. No packet can
        // start inside it (its '>' would have to be at byte 15 here too).
        ++counters_.bad_nibble;
        at += kFalconPacketBytes;
        break;
      default: {
        // A '<' not followed by a packet (a truncated one, then the next):
        // go on from the next '<' after it.
        const auto next =
            std::find(buffer_.begin() + static_cast<ptrdiff_t>(at) + 1, buffer_.end(), kStart);
        const auto cut = static_cast<size_t>(next - buffer_.begin()) - at;
        ++counters_.bad_framing;
        counters_.skipped_bytes += static_cast<int64_t>(cut);
        at += cut;
        break;
      }
    }
  }
  buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<ptrdiff_t>(at));
  return found;
}

}  // namespace sculpt::hal::falcon
