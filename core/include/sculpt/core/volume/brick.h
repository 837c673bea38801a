#pragma once
// One brick of the volume: either uniform (one value, O(1) memory) or the
// lossless Haar pyramid of its voxels (DESIGN.md §4).

#include <array>
#include <cstdint>
#include <memory>
#include <span>

#include "sculpt/core/wavelet/wavelet_pyramid.h"

namespace sculpt::core {

class Brick {
 public:
  /// A uniform brick of `value`.
  explicit Brick(uint8_t value = 0) : value_(value) {}
  Brick(Brick&&) noexcept = default;
  Brick& operator=(Brick&&) noexcept = default;
  Brick(const Brick& other);
  Brick& operator=(const Brick& other);

  /// Encodes `voxels` (edge^3, x fastest): uniform when every voxel is equal.
  /// Reuses this brick's pyramid storage when it has one.
  void encode(std::span<const uint8_t> voxels, int edge, int levels);
  /// The same result as encode() when `voxels` differ from the brick's
  /// current voxels only inside [lo, hi) (brick-local voxel coordinates):
  /// a detailed brick that stays detailed re-encodes only the coefficients
  /// over that box (WaveletPyramid::encode_region).
  void encode_region(std::span<const uint8_t> voxels, int edge, int levels, std::array<int, 3> lo,
                     std::array<int, 3> hi);
  /// Reconstructs level `level` ((edge >> level)^3 values).
  void extract_level(int level, std::span<uint8_t> out) const;

  /// Whether both bricks hold the same voxels. Encoding is canonical (a
  /// brick of one value is uniform, and the lossless Haar transform of the
  /// same voxels gives the same coefficients), so this compares encodings.
  bool holds_same_voxels(const Brick& other) const;

  bool is_uniform() const { return pyramid_ == nullptr; }
  /// The value of a uniform brick.
  uint8_t uniform_value() const { return value_; }
  /// The pyramid of a non-uniform brick, else null.
  const WaveletPyramid* pyramid() const { return pyramid_.get(); }
  /// Voxel (x, y, z) of the brick, O(levels).
  uint8_t voxel(int x, int y, int z) const { return pyramid_ ? pyramid_->voxel(x, y, z) : value_; }
  size_t memory_bytes() const { return sizeof(*this) + (pyramid_ ? pyramid_->memory_bytes() : 0); }

 private:
  uint8_t value_;
  std::unique_ptr<WaveletPyramid> pyramid_;
};

}  // namespace sculpt::core
