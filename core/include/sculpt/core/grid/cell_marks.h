#pragma once
// Marks on the cells of a box, in cells of 2^3 voxels, set box by box and
// then asked about box by box, each in constant time (difference and
// summed-area tables), however many boxes were marked.
//
// The distance patch's refresh marks the voxels a changed seed reaches and
// asks, for each seed, whether its reach meets a mark.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/core/grid/box.h"

namespace sculpt::core {

class CellMarks {
 public:
  /// Clears every mark and covers `box` (voxels).
  void reset(const Box& box);
  /// Marks the cells that meet `voxels` (clipped to the box). Before finish().
  void mark(const Box& voxels);
  /// Makes the marks readable; mark() starts over after reset() only.
  void finish();

  /// Whether a marked cell meets `voxels`. After finish().
  bool any(const Box& voxels) const;
  /// Whether the cell holding voxel `v` (inside the box) is marked.
  bool marked(glm::ivec3 v) const { return flags_[cell_index(cell_of(v))] != 0; }
  /// The marks of the cells along the row of voxels (y, z) inside the box:
  /// voxel x's is at [(x - box().lo.x) >> 1].
  const uint8_t* row_marks(int y, int z) const {
    return &flags_[cell_index(cell_of({box_.lo.x, y, z}))];
  }
  const Box& box() const { return box_; }
  /// The voxels of the marked cells' bounding box, clipped to the box; empty
  /// when nothing is marked.
  Box bounds() const { return bounds_; }

 private:
  static constexpr int kShift = 1;  // cells of 2 voxels a side
  glm::ivec3 cell_of(glm::ivec3 v) const { return (v - box_.lo) >> kShift; }
  size_t cell_index(glm::ivec3 c) const {
    return (size_t(c.z) * size_t(cells_.y) + size_t(c.y)) * size_t(cells_.x) + size_t(c.x);
  }
  // Tables one larger than the cells on each axis.
  size_t table_index(glm::ivec3 c) const {
    return (size_t(c.z) * size_t(cells_.y + 1) + size_t(c.y)) * size_t(cells_.x + 1) + size_t(c.x);
  }
  // The cells [lo, hi) that meet `voxels`; false when none.
  bool cell_range(const Box& voxels, glm::ivec3& lo, glm::ivec3& hi) const;

  Box box_;
  glm::ivec3 cells_{0};
  std::vector<int32_t> table_;  // differences, then the summed marked cells
  std::vector<uint8_t> flags_;
  Box bounds_;
};

}  // namespace sculpt::core
