#pragma once
// Internal to the mesh module: marching cubes with a caller-chosen welding
// key, for the mixed-level meshes (mixed_level_mesh.cpp): over floats where
// a brick's boundary samples are interpolated from a coarser neighbour's,
// over bytes where they are all plain level voxels.

#include <cstdint>
#include <functional>

#include <glm/vec3.hpp>

#include "sculpt/core/mesh/marching_cubes.h"

namespace sculpt::core::detail {

/// Marches `cells` cells per axis from float `samples` laid out as in
/// MarchBlock ((cells + 3)^3, one sample below and two above the corners,
/// x fastest); cell (0,0,0) has its lower corner at level point `origin`.
/// seam_key(p, axis) gives the welding key of the cell edge from local grid
/// point p along `axis`, or BrickMesh::kNotSeam; it is asked only for edges
/// on the block's boundary (no others are shared). `out` is cleared first.
void march_float_cells(const float* samples, glm::ivec3 cells, glm::ivec3 origin, int level,
                       float iso, const std::function<uint64_t(glm::ivec3, int)>& seam_key,
                       BrickMesh& out);

/// The same over byte samples (plain level voxels): the same mesh as their
/// values given as floats.
void march_byte_cells(const uint8_t* samples, glm::ivec3 cells, glm::ivec3 origin, int level,
                      float iso, const std::function<uint64_t(glm::ivec3, int)>& seam_key,
                      BrickMesh& out);

}  // namespace sculpt::core::detail
