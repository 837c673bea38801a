#pragma once
// Vector distance transforms (Jones & Satherley §3.6, equations 5 and 6):
// each voxel carries the vector to its nearest known surface point, which
// raster passes hand on to neighbours (v(p) = v(q) + (q - p)), keeping the
// shortest. Unsigned distances |v| in voxel units.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/core/grid/dense_grid.h"

namespace sculpt::core {

enum class VectorScheme {
  /// Mullikin's EVDT (CVGIP:GMIP 54(6) 1992) as we read it: Danielsson's 2D
  /// scheme on every slice (rows in both y directions, each row scanned in
  /// both x directions), once per z direction, each slice first taking from
  /// the 3x3 voxels of the slice behind; every voxel is visited 8 times.
  kEvdt,
  /// Satherley & Jones' eight-pass Vector-City VDT: one raster pass per
  /// octant direction, each taking from the 3 face neighbours behind it.
  kVcvdt,
};

struct VectorSeed {
  /// Linear voxel index (DenseGrid::index).
  int32_t voxel = 0;
  /// From the voxel centre to its nearest surface point, voxel units.
  glm::vec3 to_surface{0.0f};
};

/// |v| at every voxel of a `dims` grid after propagating `seeds`.
DenseGrid<float> vector_distance(glm::ivec3 dims, const std::vector<VectorSeed>& seeds,
                                 VectorScheme scheme);

}  // namespace sculpt::core
