#pragma once
// The clay brush (issue 21): builds up flat layers. Material is added under
// the ball swept through the path, but only up to a plane: the plane fitted
// to the surface under the ball at the stroke's start (brush_field's fit:
// normal the weighted mean outward density gradient, through the weighted
// centroid of the surface voxels), moved outward by a layer of
// layer x radius_vox. A voxel becomes m + w max(0, p - m), p the plane's
// density at the voxel (the 2-voxel antialiased ramp of a hard tool's rim),
// w = strength x the ball's tool_density() / 255. Dents below the plane fill,
// material above it stays, so the top of a full-strength stroke is flat and
// the next stroke's plane lies one layer higher: repeated strokes build
// layers. Measured (tests/core/sculpt/clay_brush_test.cpp): on a slab with
// bumps of +-1.5 voxels, a stroke of the defaults (radius 8, layer 2 voxels)
// cuts the height variance under it from 0.42 to 0.0001 voxel^2, its top
// 1.97 voxels above the old mean; a second stroke on it tops out 3.79 above.
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

struct ClayBrushOptions {
  /// The swept ball's radius (voxel units) and hardness in [0, 1].
  float radius_vox = 8.0f;
  float hardness = 0.5f;
  /// How far toward the plane a voxel fills, in [0, 1].
  float strength = 1.0f;
  /// The layer's height above the surface, as a fraction of the radius, in
  /// [0, 1].
  float layer = 0.25f;
};

/// The options from outside checked: radius in (0, kMaxBrushRadiusVox],
/// hardness, strength and layer in [0, 1]; the error names the field.
Status check_clay_brush(const ClayBrushOptions& options);

/// Builds a layer on `volume` (the volume `sculptor` sculpts, asserted) under
/// the ball swept through `path` (at least one sample; options checked,
/// asserted). Returns the voxels changed (0 when no surface lies under the
/// start).
int64_t clay_stroke(Volume& volume, Sculptor& sculptor, std::span<const StrokeSample> path,
                    const ClayBrushOptions& options);

}  // namespace sculpt::core
