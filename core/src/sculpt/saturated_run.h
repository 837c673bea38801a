#pragma once
// Where a row of material can change: a voxel already at the value a mode
// drives towards (255 adding, 0 subtracting) stays there whatever the tool
// holds, so a dab (sculptor.cpp) rotates and combines, and a stroke
// (stroke.cpp) measures and combines, only the stretch between a row's
// saturated ends. Private to core/src/sculpt.

#include <cstdint>
#include <cstring>

namespace sculpt::core {

inline uint64_t load_u64(const uint8_t* p) {
  uint64_t v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

/// Narrows [c0, c1) of `row` past the voxels equal to `saturated` at both
/// ends, eight at a time through long saturated stretches. Reads only
/// row[c0, c1).
inline void trim_saturated(const uint8_t* row, uint8_t saturated, int& c0, int& c1) {
  const uint64_t word = 0x0101010101010101ull * saturated;
  while (c0 + 8 <= c1 && load_u64(row + c0) == word)
    c0 += 8;
  while (c0 < c1 && row[c0] == saturated)
    ++c0;
  while (c1 - 8 >= c0 && load_u64(row + c1 - 8) == word)
    c1 -= 8;
  while (c1 > c0 && row[c1 - 1] == saturated)
    --c1;
}

}  // namespace sculpt::core
