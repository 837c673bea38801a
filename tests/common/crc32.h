#pragma once
// CRC-32 (zlib's polynomial) written out, so a test can seal bytes it made
// without linking zlib: the tests that hand readers damaged-but-checksummed
// files use it.

#include <cstdint>
#include <vector>

namespace sculpt::test {

inline uint32_t crc32_of(const std::vector<uint8_t>& bytes) {
  uint32_t crc = 0xffffffffu;
  for (uint8_t b : bytes) {
    crc ^= b;
    for (int k = 0; k < 8; ++k)
      crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

}  // namespace sculpt::test
