#pragma once
// Byte-level report builders for the parser tests: what a device puts on the wire.

#include <cstdint>
#include <initializer_list>
#include <vector>

#include "sculpt/hal/types/raw_event.h"

namespace sculpt::hal::test {

/// Report id followed by little-endian int16 values.
inline std::vector<uint8_t> axes_report(uint8_t id, std::initializer_list<int16_t> values) {
  std::vector<uint8_t> b{id};
  for (int16_t v : values) {
    b.push_back(static_cast<uint8_t>(v & 0xFF));
    b.push_back(static_cast<uint8_t>((v >> 8) & 0xFF));
  }
  return b;
}

inline RawEvent report_at(int64_t t_ns, const std::vector<uint8_t>& bytes) {
  return RawEvent::report(t_ns, bytes);
}

}  // namespace sculpt::hal::test
