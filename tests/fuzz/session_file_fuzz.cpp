// libFuzzer target: the binary session reader must refuse or truncate any
// input with one message, never crash, hang or allocate without bound.
// Each input is read twice: as it is, and re-sealed (the header's and every
// record's CRC-32 written over with the right value), so the mutations also
// reach the fields behind the checksums: the structured mutation a CRC
// would otherwise stop at the first byte. Seeds: sim/sessions/*.scs.

#include <zlib.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include "sculpt/sim/session/session_file.h"

namespace {

uint32_t read_u32(const uint8_t* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

void write_crc(std::vector<uint8_t>& bytes, size_t from, size_t to) {
  const uint32_t c =
      static_cast<uint32_t>(crc32(0, bytes.data() + from, static_cast<uInt>(to - from)));
  for (int i = 0; i < 4; ++i)
    bytes[to + size_t(i)] = static_cast<uint8_t>(c >> (8 * i));
}

// The layout of session_file.h: magic (8), version and flags (2 + 2),
// header length n (4), n bytes, CRC; then records of kind, flags, length
// (2), time (8), payload, CRC.
std::vector<uint8_t> resealed(std::span<const uint8_t> data) {
  std::vector<uint8_t> bytes(data.begin(), data.end());
  if (bytes.size() < 16) return bytes;
  const size_t fields_end = 16 + size_t(read_u32(&bytes[12]));
  if (fields_end + 4 > bytes.size()) return bytes;
  write_crc(bytes, 16, fields_end);
  size_t at = fields_end + 4;
  while (at + 12 <= bytes.size()) {
    const size_t length = size_t(bytes[at + 2]) | size_t(bytes[at + 3]) << 8;
    const size_t end = at + 12 + length;
    if (end + 4 > bytes.size()) break;
    write_crc(bytes, at, end);
    at = end + 4;
  }
  return bytes;
}

void read_and_check(std::span<const uint8_t> bytes) {
  sculpt::sim::SessionReadInfo info;
  auto session = sculpt::sim::parse_session_bytes(bytes, "fuzz.scs", &info);
  if (session.ok()) {
    // Whatever was accepted must write back and read again identically.
    const std::vector<uint8_t> again = sculpt::sim::serialize_session(*session);
    auto back = sculpt::sim::parse_session_bytes(again, "again.scs");
    if (!back.ok() || !(*back == *session)) __builtin_trap();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  read_and_check(std::span(data, size));
  read_and_check(resealed(std::span(data, size)));
  return 0;
}
