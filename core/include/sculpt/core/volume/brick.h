#pragma once
// One brick of the volume: either uniform (one value, O(1) memory) or the
// lossless Haar pyramid of its voxels (DESIGN.md §4).
//
// Copies share the pyramid (copy on write). The sculpting thread copies
// bricks all the time: the undo history keeps a stroke's bricks as they
// were, the mesher is handed each changed brick, and the autosave a whole
// volume. Shared, each such copy is a pointer and a count, where it was a
// copy of up to 64 KiB of coefficients (4.5 ms for a 512^3 volume, on the
// thread that applies the dabs); a brick pays for its copy only when it is
// encoded again while shared.

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <span>

#include "sculpt/core/wavelet/wavelet_pyramid.h"

namespace sculpt::core {

class Brick {
 public:
  /// A uniform brick of `value`.
  explicit Brick(uint8_t value = 0) : value_(value) {}
  Brick(Brick&& other) noexcept;
  Brick& operator=(Brick&& other) noexcept;
  /// Shares the other brick's pyramid, O(1). From then on no holder changes
  /// it: the next encode of either brick makes a pyramid of its own.
  Brick(const Brick& other);
  Brick& operator=(const Brick& other);

  /// Encodes `voxels` (edge^3, x fastest): uniform when every voxel is equal.
  /// Reuses this brick's pyramid storage when it has one of its own.
  void encode(std::span<const uint8_t> voxels, int edge, int levels);
  /// The same result as encode() when `voxels` differ from the brick's
  /// current voxels only inside [lo, hi) (brick-local voxel coordinates):
  /// a detailed brick that stays detailed re-encodes only the coefficients
  /// over that box (WaveletPyramid::encode_region), on a copy of its
  /// pyramid when that is shared.
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
  /// Whether the pyramid is shared with a copy (so encoding copies it first).
  bool shares_pyramid() const { return shared_.load(std::memory_order_relaxed); }
  /// Voxel (x, y, z) of the brick, O(levels).
  uint8_t voxel(int x, int y, int z) const { return pyramid_ ? pyramid_->voxel(x, y, z) : value_; }
  /// The bytes this brick would hold on its own (a shared pyramid counts in
  /// full: it becomes this brick's alone when the other holders let go).
  size_t memory_bytes() const { return sizeof(*this) + (pyramid_ ? pyramid_->memory_bytes() : 0); }

 private:
  // A pyramid of `edge` and `levels` that only this brick holds, for
  // encode() to write over (its coefficients are not kept).
  WaveletPyramid& own_blank_pyramid(int edge, int levels);

  uint8_t value_;
  std::shared_ptr<WaveletPyramid> pyramid_;
  // Set on both bricks when a copy shares pyramid_, and never cleared while
  // they hold it: a shared pyramid is read-only for every holder, so readers
  // on other threads (the mesher's mirror, the autosave) need no lock. A
  // copy is made under const access, which the volume's contract keeps
  // apart from the editing that reads this flag; atomic only because const
  // copies of one brick may be made on several threads at once.
  mutable std::atomic<bool> shared_{false};
};

}  // namespace sculpt::core
