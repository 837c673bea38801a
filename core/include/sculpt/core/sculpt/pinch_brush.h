#pragma once
// The pinch (crease) brush (issue 21): pulls the surface under the ball
// swept through the path toward the path's line. A voxel at r from its
// nearest path point c takes the material as it was at c + (1 + w) r
// (trilinear; w = strength x the ball's tool_density() / 255), so what lay
// (1 + w) times as far now lies here: along a groove cut by a subtract
// stroke the walls close in (a crease), along a ridge built by an add
// stroke its flanks steepen. The map folds (skips material) where w falls
// faster than 1 / r, which a ball of hardness above about 0.3 does at full
// strength: the default is a soft ball. Measured
// (tests/core/sculpt/pinch_brush_test.cpp): a groove cut by a radius-5 ball
// narrows at half depth from 8.60 to 6.26 voxels under a stroke of radius 10
// (other options the defaults), its depth going from 5.00 to 3.66: the floor
// is pulled toward the line too.
//
// One undo step through Sculptor::external_edit(). As the smooth brush, it
// ignores the sculptor's mirror plane: the station's panel offers it and runs
// it again along the mirrored path (station_loop.cpp).

#include <cstdint>
#include <span>

#include "sculpt/base/result.h"
#include "sculpt/core/grid/box.h"
#include "sculpt/core/sculpt/brush_limits.h"
#include "sculpt/core/sculpt/stroke.h"

namespace sculpt::core {

struct PinchBrushOptions {
  /// The swept ball's radius (voxel units) and hardness in [0, 1].
  float radius_vox = 8.0f;
  float hardness = 0.0f;
  /// How strongly, in [0, 1]: 1 pulls what lay twice as far to the centre.
  float strength = 0.5f;
};

/// The options from outside checked: radius in (0, kMaxBrushRadiusVox],
/// hardness and strength in [0, 1]; the error names the field.
Status check_pinch_brush(const PinchBrushOptions& options);

/// Pinches `volume` (the volume `sculptor` sculpts, asserted) toward the
/// path (at least one sample; options checked, asserted). Returns the voxels
/// changed.
int64_t pinch_stroke(Volume& volume, Sculptor& sculptor, std::span<const StrokeSample> path,
                     const PinchBrushOptions& options);

/// What pinch_stroke() writes within `part` (clipped to the path's reach),
/// reading the material as it was before the stroke from `before` (the
/// volume's dims, asserted; read within `part` grown by
/// pinch_read_margin()) whatever `volume` holds there now. A voxel's result
/// depends only on the material around it, its weight and the path's
/// nearest point, which samples that do not reach it leave as they were: a
/// preview of a grown path re-pinches only what the new samples reach.
int64_t pinch_stroke_part(Volume& volume, Sculptor& sculptor, std::span<const StrokeSample> path,
                          const PinchBrushOptions& options, const Box& part, const Volume& before);
/// How far beyond the voxels it writes pinch_stroke_part() reads `before`.
int pinch_read_margin(const PinchBrushOptions& options);

}  // namespace sculpt::core
