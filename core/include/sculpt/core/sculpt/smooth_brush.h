#pragma once
// The smooth brush (issue 21): along a stroke, the material under a ball
// swept through the path moves toward a blurred copy of itself, so the
// surface's small bumps flatten while its shape and volume stay.
//
// The blur is `passes` rounds of the separable [1 2 1] / 4 filter along x,
// y and z (a binomial approximation of a Gaussian of variance passes / 2
// voxel^2 per axis), over the material as it was before the stroke; a voxel
// moves by weight w = strength x (the swept ball's tool_density() / 255),
// once per stroke (the largest weight the path gives it, as SweptStroke).
// The blur keeps the density's sum, so the volume changes only by the
// surface's curvature flow: under a stroke of the defaults a radius-30 ball's
// surface moves in by 0.07 voxel, and a noisy one's mean angle between
// neighbouring vertex normals falls from 0.25 to 0.04 rad with its volume
// kept within 0.01% (tests/core/sculpt/smooth_brush_test.cpp).
//
// One undo step through Sculptor::external_edit(). Not yet: the sculptor's
// mirror plane, the station's brush panel. Each segment of the path measures
// the distance of the voxels within its reach only, so the cost grows with
// the path's length times the ball's cross-section.

#include <cstdint>
#include <span>

#include "sculpt/base/result.h"
#include "sculpt/core/grid/box.h"
#include "sculpt/core/sculpt/brush_limits.h"
#include "sculpt/core/sculpt/stroke.h"

namespace sculpt::core {

struct SmoothBrushOptions {
  /// The swept ball's radius (voxel units, > 0) and hardness in [0, 1].
  float radius_vox = 8.0f;
  float hardness = 0.5f;
  /// How far toward the blurred material, in [0, 1].
  float strength = 1.0f;
  /// Blur rounds, >= 1: more smooths larger bumps.
  int passes = 4;
};

/// Most blur rounds accepted: 64 rounds blur over about 6 voxels each way.
inline constexpr int kMaxSmoothPasses = 64;

/// The options from outside (a script, a setting) checked: radius in
/// (0, kMaxBrushRadiusVox], hardness and strength in [0, 1], passes in
/// [1, kMaxSmoothPasses]; the error names the field ('radius', ...).
Status check_smooth_brush(const SmoothBrushOptions& options);

/// Smooths `volume` (the volume `sculptor` sculpts, asserted) under the ball
/// swept through `path` (at least one sample; options checked, asserted).
/// Returns the voxels changed.
int64_t smooth_stroke(Volume& volume, Sculptor& sculptor, std::span<const StrokeSample> path,
                      const SmoothBrushOptions& options);

/// What smooth_stroke() writes within `part` (clipped to the path's reach),
/// reading the material as it was before the stroke from `before` (the
/// volume's dims, asserted; read within `part` grown by options.passes)
/// whatever `volume` holds there now; the rest of `volume` is left as it
/// is. A voxel's result depends only on the material around it and its
/// weight, the largest the path gives it: a preview of a path grown by a
/// few samples re-smooths the part their segments reach and leaves the
/// rest of the last preview as it was (station/app/brush_preview.h).
int64_t smooth_stroke_part(Volume& volume, Sculptor& sculptor, std::span<const StrokeSample> path,
                           const SmoothBrushOptions& options, const Box& part,
                           const Volume& before);
/// How far beyond the voxels it writes smooth_stroke_part() reads `before`.
inline int smooth_read_margin(const SmoothBrushOptions& options) {
  return options.passes;
}

}  // namespace sculpt::core
