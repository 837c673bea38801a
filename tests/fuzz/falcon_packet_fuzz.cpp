// libFuzzer target: the bytes a Falcon (or a broken cable, or something
// pretending to be a Falcon) sends back, as the FalconPacketReader sees them
// after the FTDI status bytes are gone. Input: chunks, each preceded by its
// length byte (as USB transfers split the stream). Checks: no crash, at
// most one partial packet held, a packet decoded alone agrees with the
// reader, and every decoded packet re-encodes to the encoders it gave.
// Seeds: corpus/falcon_packet.

#include <cstddef>
#include <cstdint>
#include <span>

#include "backends/falcon/falcon_packet.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace sculpt::hal::falcon;
  FalconPacketReader reader;
  for (size_t at = 0; at < size;) {
    const size_t length = std::min<size_t>(data[at], size - at - 1);
    reader.feed(std::span(data + at + 1, length));
    if (reader.partial() >= kFalconPacketBytes) __builtin_trap();
    at += 1 + length;
  }
  // The whole input as one packet, the way a single read would see it.
  FalconInput in;
  if (decode_falcon_input(std::span(data, size), in) == FalconPacketError::kNone) {
    if (in.homed > 7 || in.buttons > 15) __builtin_trap();
    FalconOutput out;
    out.motor = in.encoder;
    const FalconPacket p = encode_falcon_output(out);
    FalconInput back;
    if (decode_falcon_input(p, back) != FalconPacketError::kNone || back.encoder != in.encoder)
      __builtin_trap();
  }
  return 0;
}
