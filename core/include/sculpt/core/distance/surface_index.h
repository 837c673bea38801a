#pragma once
// The triangles of a level function's zero level (iso_triangulation.h),
// indexed by cell, for nearest-surface-point searches near the surface.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "sculpt/core/distance/iso_triangulation.h"
#include "sculpt/core/grid/dense_grid.h"

namespace sculpt::core {

class SurfaceIndex {
 public:
  /// Triangulates every transverse cell of `phi` (in parallel).
  explicit SurfaceIndex(const DenseGrid<float>& phi, int threads = 0);

  const std::vector<Triangle3>& triangles() const { return triangles_; }
  /// Cells span voxel centres: dims - 1 per axis (0 when dims < 2).
  glm::ivec3 cell_dims() const { return cell_dims_; }

  /// The triangles of cell c (lower corner), empty when not transverse.
  std::pair<const Triangle3*, const Triangle3*> cell(glm::ivec3 c) const {
    const size_t i = first_.index(c.x, c.y, c.z);
    const Triangle3* b = triangles_.data() + first_[i];
    return {b, b + count_[i]};
  }

  struct Nearest {
    glm::vec3 point{0.0f};
    /// Squared distance to it (+inf when no surface lies within max_radius).
    float distance_squared = 0.0f;
    /// Index of its triangle in triangles() (-1 when none was found).
    int32_t triangle = -1;
  };
  /// The nearest point of the surface to voxel p, searching cells in rings
  /// of growing Chebyshev radius until no nearer cell can exist; exact
  /// whenever the nearest point is within max_radius voxels.
  Nearest nearest(glm::ivec3 p, int max_radius = 8) const;
  /// The nearest point to p among `best` and the triangles of the cells
  /// with lower corner in [lo, hi] (clamped to the grid of cells). p may be
  /// anywhere; only those cells are searched.
  Nearest nearest_in_cells(glm::vec3 p, glm::ivec3 lo, glm::ivec3 hi, Nearest best) const;

 private:
  glm::ivec3 cell_dims_{0};
  std::vector<Triangle3> triangles_;
  /// Per triangle: centre and radius of a ball holding it (cheap rejection).
  std::vector<glm::vec4> bounds_;
  DenseGrid<int32_t> first_;
  DenseGrid<uint8_t> count_;
};

}  // namespace sculpt::core
