#pragma once
// The flatten brush (issue 21): moves the surface under the ball swept
// through the path toward the plane fitted to it (brush_field's fit over the
// whole swept ball: normal the weighted mean outward density gradient,
// through the weighted centroid of the surface voxels). A voxel becomes
// m + w (p - m), p the plane's density at the voxel (a hard tool rim's
// 2-voxel ramp), w = strength x the ball's tool_density() / 255: below the
// plane material is added, above it removed. Any material within the ball
// counts, so a stroke near another part of the sculpture flattens that too.
// Measured (tests/core/sculpt/flatten_brush_test.cpp): on a slab with bumps
// of +-1.5 voxels, a stroke of the defaults (radius 8) cuts the height
// variance under it from 0.42 to below 0.0001 voxel^2, its mean height
// moving 0.01 voxel, the volume kept within 1%.
//
// One undo step through Sculptor::external_edit(). As the smooth brush, it
// ignores the sculptor's mirror plane: the station's panel offers it and runs
// it again along the mirrored path (station_loop.cpp).

#include <cstdint>
#include <span>

#include "sculpt/base/result.h"
#include "sculpt/core/sculpt/brush_limits.h"
#include "sculpt/core/sculpt/stroke.h"

namespace sculpt::core {

struct FlattenBrushOptions {
  /// The swept ball's radius (voxel units) and hardness in [0, 1].
  float radius_vox = 8.0f;
  float hardness = 0.5f;
  /// How far toward the plane, in [0, 1].
  float strength = 1.0f;
};

/// The options from outside checked: radius in (0, kMaxBrushRadiusVox],
/// hardness and strength in [0, 1]; the error names the field.
Status check_flatten_brush(const FlattenBrushOptions& options);

/// Flattens `volume` (the volume `sculptor` sculpts, asserted) under the ball
/// swept through `path` (at least one sample; options checked, asserted).
/// Returns the voxels changed (0 when no surface lies under the ball).
int64_t flatten_stroke(Volume& volume, Sculptor& sculptor, std::span<const StrokeSample> path,
                       const FlattenBrushOptions& options);

}  // namespace sculpt::core
