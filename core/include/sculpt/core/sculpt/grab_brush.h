#pragma once
// The grab brush (issue 21): drags the material under the ball along the
// stroke's displacement D (its first sample to its last; the samples
// between are not used). The ball moves from the first sample to the last
// in n equal steps, each carrying the material by w(y) D / n, w = strength x
// the ball's tool_density() / 255 at y's distance from the ball's centre
// then; each voxel x takes the material as it was where those steps bring
// it from (each step's inverse solved by fixed-point iteration, starting at
// x - w(x) D / n, trilinear sampling). n is the least that keeps each step
// from folding (|D| / n times the falloff's steepest slope <= 1/2), so a
// long drag stays a smooth, invertible warp (up to 256 steps: a longer drag,
// over 170 voxels for a hard ball, takes longer steps and may fold). Cost:
// the capsule's voxels times the steps. Material within the ball's
// full-weight core moves rigidly, so a bump there keeps its volume.
// Measured (tests/core/sculpt/grab_brush_test.cpp): a bump of radius 3 on a
// slab dragged by (7.5, 2.5, 0) voxels with a ball of radius 16 moves its
// centroid by (7.500, 2.500, 0.000), its volume kept within 0.04%.
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

struct GrabBrushOptions {
  /// The swept ball's radius (voxel units) and hardness in [0, 1].
  float radius_vox = 8.0f;
  float hardness = 0.5f;
  /// The part of the displacement the ball's centre carries, in [0, 1].
  float strength = 1.0f;
};

/// The options from outside checked: radius in (0, kMaxBrushRadiusVox],
/// hardness and strength in [0, 1]; the error names the field.
Status check_grab_brush(const GrabBrushOptions& options);

/// Drags the material of `volume` (the volume `sculptor` sculpts, asserted)
/// along `path` (at least one sample; options checked, asserted). Returns the
/// voxels changed (0 when the path does not move).
int64_t grab_stroke(Volume& volume, Sculptor& sculptor, std::span<const StrokeSample> path,
                    const GrabBrushOptions& options);

}  // namespace sculpt::core
