#pragma once
// Morphology on sub-voxel distance fields (Jones & Satherley §4.2): offsets
// and the true 3D closing. Fields are float32, voxel units, negative inside;
// distances use the hybrid exact method (signed_distance.h, exact + shell).

#include "sculpt/core/grid/dense_grid.h"

namespace sculpt::core {

/// The signed distance field of phi's zero level (exact, shell init).
DenseGrid<float> surface_distance(const DenseGrid<float>& phi, int threads = 0);

/// The surface moved outward by `by` voxels (inward when negative): the
/// distance field of the offset surface, D - by.
DenseGrid<float> offset_distance(const DenseGrid<float>& distance, float by);

/// True closing by `radius` voxels: D = distance to the surface; the dilated
/// surface is {D = radius}; D' = distance to that surface, re-computed; the
/// closed surface is {D' = -radius}. Returns D' + radius (negative inside the
/// closed shape). `phi` is any level function (negative inside).
DenseGrid<float> close_distance(const DenseGrid<float>& phi, float radius, int threads = 0);

}  // namespace sculpt::core
