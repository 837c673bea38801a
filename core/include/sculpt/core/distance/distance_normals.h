#pragma once
// Smooth surface normals from a distance field (Jones & Satherley §2: the
// gradient of D points away from the object and is perpendicular to the
// surface). Central differences at the 8 voxels around a point, trilinearly
// interpolated; voxel units; clamped at the grid's faces.

#include <glm/vec3.hpp>

#include "sculpt/core/grid/dense_grid.h"
#include "sculpt/core/mesh/mesh.h"

namespace sculpt::core {

/// The field's trilinear value at p (voxel coordinates), clamped onto the
/// grid as distance_gradient(); any float field (a density too).
float sample_trilinear(const DenseGrid<float>& field, glm::vec3 p);
/// Gradient of `distance` at p (voxel coordinates), per voxel unit.
glm::vec3 distance_gradient(const DenseGrid<float>& distance, glm::vec3 p);
/// The unit gradient at p ((0,0,0) where the gradient vanishes).
glm::vec3 distance_normal(const DenseGrid<float>& distance, glm::vec3 p);
/// Sets mesh.normals from the field at every vertex position.
void set_normals_from_distance(const DenseGrid<float>& distance, Mesh& mesh);

}  // namespace sculpt::core
