#pragma once
// The exact signed distance to a level function's zero level, only in a
// narrow band around it: what a narrow-band level set (OpenVDB's, written
// to .vdb) holds, without the whole-grid transform of signed_distance().

#include "sculpt/core/grid/dense_grid.h"
#include "sculpt/core/util/progress.h"

namespace sculpt::core {

/// Per voxel of `phi`: the signed distance (voxel units, negative where phi
/// < 0) to the tiling-tetrahedra triangulation of phi's zero level (the
/// surface signed_distance(kExact, kShell) and `sculpt distance` measure),
/// for every voxel nearer to it than `half_width`; +-infinity, signed as phi,
/// for the others. Each band voxel searches only the cells around it
/// (SurfaceIndex::nearest), so the cost follows the surface's area, not the
/// grid's volume. The result does not depend on `threads`. `progress`
/// (optional, progress.h) counts slices; a cancelled call returns a grid to
/// discard.
DenseGrid<float> surface_band_distance(const DenseGrid<float>& phi, float half_width,
                                       int threads = 0, Progress* progress = nullptr);

}  // namespace sculpt::core
