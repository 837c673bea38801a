#pragma once
// Octree-accelerated exact distance (Jones & Satherley §3.3): the same
// result as brute_distance.h, found by descending an octree over the
// primitives and rejecting every node farther than the best distance so far.
// As in the paper, each voxel starts from the primitive that was nearest to
// the previous voxel of its row, which rejects most of the tree at once.
// Rows run in parallel. Unsigned distances, voxel units.

#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/core/distance/iso_triangulation.h"
#include "sculpt/core/grid/dense_grid.h"

namespace sculpt::core {

DenseGrid<float> octree_distance_to_points(glm::ivec3 dims, const std::vector<glm::vec3>& points,
                                           int threads = 0);
DenseGrid<float> octree_distance_to_triangles(glm::ivec3 dims,
                                              const std::vector<Triangle3>& triangles,
                                              int threads = 0);

}  // namespace sculpt::core
