#pragma once
// The naive exact distance of Jones & Satherley §3.1 (to seed voxels) and
// §3.2 (to triangles): every voxel against every primitive, O(n m). The
// reference the faster methods are tested against; small volumes only.
// Unsigned distances in voxel units; +infinity when there are no primitives.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/core/distance/iso_triangulation.h"
#include "sculpt/core/grid/dense_grid.h"

namespace sculpt::core {

/// Distance from each voxel of a `dims` grid to the nearest of `points`.
DenseGrid<float> brute_distance_to_points(glm::ivec3 dims, const std::vector<glm::vec3>& points,
                                          int threads = 0);
/// Distance from each voxel of a `dims` grid to the nearest of `triangles`.
DenseGrid<float> brute_distance_to_triangles(glm::ivec3 dims,
                                             const std::vector<Triangle3>& triangles,
                                             int threads = 0);

/// Positions of the voxels of `mask` equal to `value`, in index order.
std::vector<glm::vec3> voxel_positions(const DenseGrid<uint8_t>& mask, uint8_t value);

}  // namespace sculpt::core
