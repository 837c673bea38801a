#pragma once
// The lossless 3D Haar pyramid of one cube of voxels (a brick).
//
// "Discrete tools for virtual sculpture" §2.2: per level, the 1D Haar step is
// applied along x, then y, then z (Pinnamaneni's hierarchy). The step is the
// integer S-transform of haar_1d.h, so uint8 voxels reconstruct bit for bit.
//
// Coefficient layout (edge e, levels L), in one e^3 array of int16, x fastest:
//  - the level-L low-pass cube (the "LLL" block) is [0, e >> L)^3;
//  - the detail bands of level l (1 <= l <= L) are the seven octants of the
//    cube [0, e >> (l - 1))^3 other than its first; octant (bx, by, bz) in
//    {0,1}^3 starts at (bx, by, bz) * (e >> l), and a 1 means "high-pass along
//    that axis" (so (1,0,0) is the paper's H block after the x step).
//
// Ranges: low-pass values stay in [0, 255]; a detail that went through k
// high-pass steps lies in [-255 * 2^(k-1), 255 * 2^(k-1)], at most +-1020,
// so int16 holds every coefficient.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace sculpt::core {

class WaveletPyramid {
 public:
  /// Largest supported brick edge (a 128^3 brick holds 7 levels).
  static constexpr int kMaxEdge = 128;

  /// A pyramid of a cube of `edge` voxels (a power of two, 2..kMaxEdge) with
  /// `levels` levels (0..log2(edge)); all coefficients zero.
  WaveletPyramid(int edge, int levels);

  int edge() const { return edge_; }
  int levels() const { return levels_; }

  /// Decomposes `voxels` (edge^3, x fastest) into this pyramid.
  void encode(std::span<const uint8_t> voxels);
  /// Brings the pyramid up to date with `voxels` (edge^3, x fastest) when
  /// they differ from the ones it holds only inside the box [lo, hi) (voxel
  /// coordinates, x y z, non-empty): recomputes only the coefficients whose
  /// support meets the box, level by level (plus the inverse steps that
  /// recover the unchanged low-pass values around it), so the cost follows
  /// the box rather than the brick. The result equals encode(voxels)
  /// coefficient for coefficient.
  void encode_region(std::span<const uint8_t> voxels, std::array<int, 3> lo, std::array<int, 3> hi);
  /// Reconstructs the voxels exactly (edge^3, x fastest).
  void decode(std::span<uint8_t> voxels) const;
  /// The low-pass cube of `level` (0 = the voxels themselves): (edge >> level)^3
  /// values, x fastest. Each value is the S-transform's floor-average of the
  /// 2^level cube of voxels it covers.
  void extract_level(int level, std::span<uint8_t> out) const;
  /// One voxel of level 0, reconstructed from L coefficients per level: O(levels).
  uint8_t voxel(int x, int y, int z) const;

  /// The coefficients in the layout described above.
  std::span<const int16_t> coefficients() const { return coefficients_; }
  std::span<int16_t> coefficients() { return coefficients_; }

  /// Number of detail coefficients (all but the level-L low-pass block).
  int64_t detail_count() const;
  /// Number of detail coefficients equal to zero: a measure of how well the
  /// brick would compress.
  int64_t zero_detail_count() const;
  size_t memory_bytes() const { return sizeof(*this) + coefficients_.size() * sizeof(int16_t); }

 private:
  int edge_;
  int levels_;
  std::vector<int16_t> coefficients_;
};

/// log2 of a power of two.
int log2_exact(int power_of_two);
/// Whether n is a power of two (n > 0).
constexpr bool is_power_of_two(int n) {
  return n > 0 && (n & (n - 1)) == 0;
}

}  // namespace sculpt::core
