#pragma once
// The voxel-by-voxel combination of a dab with the material (§3.3 of
// "Discrete tools for virtual sculpture"), one row at a time.

#include <cstddef>
#include <cstdint>

namespace sculpt::core {

enum class SculptMode;

/// Bytes past a row's end that combine_row() may read, and rewrite with their
/// own values: a row's buffers must extend this far.
inline constexpr size_t kCombineRowSlack = 32;

/// Combines tool values f[0 .. n) (rotated densities 0..255), scaled to the
/// filling (f q + 128) >> 8 with q = strength * 256 in [0, 256], into the
/// material m[0 .. n) by `mode` (not kSmooth, which needs neighbours).
/// Returns how many voxels of m changed. m and f must stay readable, m also
/// writable, for kCombineRowSlack bytes past n; those bytes keep their
/// values (not safe if another thread writes them meanwhile). Uses AVX2 when
/// the CPU has it; the result is that of combine_row_scalar() either way.
int64_t combine_row(SculptMode mode, uint8_t* m, const uint8_t* f, int n, uint32_t q);

/// The same, one voxel at a time and without the slack (the reference).
int64_t combine_row_scalar(SculptMode mode, uint8_t* m, const uint8_t* f, int n, uint32_t q);

}  // namespace sculpt::core
