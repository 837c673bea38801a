#pragma once
// The inflate brush (issue 21): pushes the surface under the ball swept
// through the path outward along its normal, by w x distance_vox voxels
// (w = strength x the ball's tool_density() / 255): each voxel takes the
// material as it was at x - n(x) w distance_vox (trilinear), a dilation of
// the density. The normal n is the outward gradient of the density blurred
// enough that it is defined as far from the surface as the surface moves.
// Measured (tests/core/sculpt/inflate_brush_test.cpp): a hard ball covering a
// radius-20 sphere, distance 2, takes its radius over 200 directions from
// 19.98..20.00 to 21.95..22.00, and the volume grows monotonically with the
// strength.
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

/// Farthest one inflate stroke moves the surface, in voxels.
inline constexpr float kMaxInflateDistanceVox = 8.0f;

struct InflateBrushOptions {
  /// The swept ball's radius (voxel units) and hardness in [0, 1].
  float radius_vox = 8.0f;
  float hardness = 0.5f;
  /// Scales the move, in [0, 1].
  float strength = 1.0f;
  /// How far the surface moves at full weight, voxels in
  /// (0, kMaxInflateDistanceVox].
  float distance_vox = 1.0f;
};

/// The options from outside checked: radius in (0, kMaxBrushRadiusVox],
/// hardness and strength in [0, 1], distance in (0, kMaxInflateDistanceVox];
/// the error names the field.
Status check_inflate_brush(const InflateBrushOptions& options);

/// Inflates `volume` (the volume `sculptor` sculpts, asserted) under the ball
/// swept through `path` (at least one sample; options checked, asserted).
/// Returns the voxels changed.
int64_t inflate_stroke(Volume& volume, Sculptor& sculptor, std::span<const StrokeSample> path,
                       const InflateBrushOptions& options);

/// What inflate_stroke() writes within `part` (clipped to the path's
/// reach), reading the material as it was before the stroke from `before`
/// (the volume's dims, asserted; read within `part` grown by
/// inflate_read_margin()) whatever `volume` holds there now; the rest of
/// `volume` is left as it is. A voxel's result depends only on the material
/// around it and its weight: a preview of a grown path re-inflates only what
/// the new samples reach (as smooth_stroke_part()).
int64_t inflate_stroke_part(Volume& volume, Sculptor& sculptor, std::span<const StrokeSample> path,
                            const InflateBrushOptions& options, const Box& part,
                            const Volume& before);
/// How far beyond the voxels it writes inflate_stroke_part() reads `before`.
int inflate_read_margin(const InflateBrushOptions& options);

}  // namespace sculpt::core
