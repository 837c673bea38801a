#pragma once
// Morphology on sub-voxel distance fields (Jones & Satherley §4.2): offsets
// and the true 3D closing. Fields are float32, voxel units, negative inside;
// distances use the hybrid exact method (signed_distance.h, exact + shell).

#include "sculpt/core/grid/dense_grid.h"
#include "sculpt/core/util/progress.h"

namespace sculpt::core {

/// The signed distance field of phi's zero level (exact, shell init).
/// `progress` (optional, progress.h): a cancelled call returns a field to
/// discard (here and in close_distance).
DenseGrid<float> surface_distance(const DenseGrid<float>& phi, int threads = 0,
                                  Progress* progress = nullptr);

/// The surface moved outward by `by_vox` voxels (inward when negative): the
/// distance field of the offset surface, D - by_vox.
DenseGrid<float> offset_distance(const DenseGrid<float>& distance, float by_vox);

/// True closing by `radius_vox` voxels: D = distance to the surface; the dilated
/// surface is {D = radius_vox}; D' = distance to that surface, re-computed; the
/// closed surface is {D' = -radius_vox}. Returns D' + radius_vox (negative inside the
/// closed shape). `phi` is any level function (negative inside).
DenseGrid<float> close_distance(const DenseGrid<float>& phi, float radius_vox, int threads = 0,
                                Progress* progress = nullptr);

}  // namespace sculpt::core
