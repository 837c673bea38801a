#pragma once
// The 16-byte packet of the Novint SDK firmware, the one the Falcon runs once
// its firmware is loaded (falcon_firmware.h). Every packet the host sends is
// answered by one from the device; the host drives the exchange, at 1 kHz.
//
//   byte  0      '<'
//   bytes 1-12   three int16, four bytes each, least significant nibble
//                first, each nibble sent as 'A' + nibble ('A'..'P')
//                  host -> device: motor commands (signed, motor units)
//                  device -> host: encoder counts (signed)
//   byte 13      'A' + flags
//                  host -> device: bit 0 homing mode, bits 1-3 LEDs
//                  device -> host: bits 0-3 buttons, bits 4-6 homed (one per motor)
//   byte 14      'A' (host); unknown (device), not checked
//   byte 15      '>'
//
// Source: libnifalcon include/falcon/firmware/FalconFirmwareNovintSDK.h (the
// layout) and src/firmware/FalconFirmwareNovintSDK.cpp (nibble order, flag
// bits); LED bits from include/falcon/core/FalconFirmware.h.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace sculpt::hal::falcon {

inline constexpr size_t kFalconPacketBytes = 16;
using FalconPacket = std::array<uint8_t, kFalconPacketBytes>;

/// LED bits of FalconOutput::leds.
enum FalconLed : uint8_t {
  kFalconLedGreen = 0x02,
  kFalconLedBlue = 0x04,
  kFalconLedRed = 0x08,
};

/// What the host sends each tick.
struct FalconOutput {
  /// Motor commands, motor units (falcon_kinematics.h makes them from newtons).
  std::array<int16_t, 3> motor{};
  /// FalconLed bits.
  uint8_t leds = 0;
  /// Homing mode: the firmware sets a motor's homed flag when its arm passes
  /// the index mark.
  bool homing = false;
};

/// What the device answers.
struct FalconInput {
  /// Encoder counts of the three motors.
  std::array<int16_t, 3> encoder{};
  /// Grip buttons, bit i = button i (4 on the standard grip).
  uint8_t buttons = 0;
  /// Bit i: motor i homed.
  uint8_t homed = 0;
  bool all_homed() const { return (homed & 7) == 7; }
};

FalconPacket encode_falcon_output(const FalconOutput& out);

enum class FalconPacketError : uint8_t {
  kNone,
  kShort,    ///< fewer than 16 bytes
  kFraming,  ///< no '<' first or no '>' last
  kNibble,   ///< a value byte outside 'A'..'P' (or byte 13 outside 'A'..'A'+127)
};

/// Decodes one device packet; `in` is written only on kNone.
FalconPacketError decode_falcon_input(std::span<const uint8_t> bytes, FalconInput& in);

/// Malformed input seen by a FalconPacketReader.
struct FalconPacketCounters {
  int64_t packets = 0;        ///< good packets decoded
  int64_t bad_framing = 0;    ///< times the stream was out of step (bytes skipped to the next '<')
  int64_t bad_nibble = 0;     ///< framed packets with a byte out of range (dropped)
  int64_t short_reads = 0;    ///< exchanges that ended mid-packet (counted by the caller)
  int64_t skipped_bytes = 0;  ///< bytes thrown away while resynchronising
};

/// Cuts a byte stream from the device into packets, whatever arrives: bytes
/// in any split, garbage between packets, truncated packets. Never throws;
/// holds at most one partial packet between calls.
class FalconPacketReader {
 public:
  /// Takes bytes; each whole good packet replaces newest(). Returns the
  /// number of good packets found in this call.
  int feed(std::span<const uint8_t> bytes);
  /// The last good packet.
  const FalconInput& newest() const { return newest_; }
  /// Bytes of an unfinished packet held over.
  size_t partial() const { return buffer_.size(); }
  void clear() { buffer_.clear(); }
  FalconPacketCounters& counters() { return counters_; }
  const FalconPacketCounters& counters() const { return counters_; }

 private:
  std::vector<uint8_t> buffer_;
  FalconInput newest_;
  FalconPacketCounters counters_;
};

}  // namespace sculpt::hal::falcon
