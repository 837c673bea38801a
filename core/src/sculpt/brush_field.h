#pragma once
// What the ball brushes (smooth, clay, flatten, inflate, pinch, grab) share,
// private to the library: the ball swept through the path and its weight,
// the material under it as it was before the stroke (floats, sampled
// trilinearly), and the one write of the result as one undo step.

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/base/result.h"
#include "sculpt/core/grid/box.h"
#include "sculpt/core/grid/dense_grid.h"
#include "sculpt/core/sculpt/brush_limits.h"
#include "sculpt/core/sculpt/sculptor.h"
#include "sculpt/core/sculpt/stroke.h"

namespace sculpt::core::brush {

/// The swept ball: radius (voxels), hardness and strength, as every brush's
/// options hold them.
struct Ball {
  float radius_vox = 8.0f;
  float hardness = 0.5f;
  float strength = 1.0f;
  /// Farthest a voxel the ball weighs can lie from the path: tool_density()
  /// is 0 from one voxel outside the ball's surface on.
  float reach() const { return radius_vox + 1.0f; }
  /// strength x the ball's tool_density() at `distance_vox` from its centre / 255.
  float weight(float distance_vox) const;
};

/// The ball's fields checked: radius in (0, kMaxBrushRadiusVox], hardness and
/// strength in [0, 1]; the error names the field ('radius', ...).
Status check_ball(const Ball& ball);
/// `value` in [lo, hi], else an error naming `key` and the range.
Status check_range(const char* key, double value, double lo, double hi);
/// A length in voxels: `value` in (0, hi], else an error naming `key`.
Status check_positive(const char* key, double value, double hi);

/// The distance from each voxel of a box to the polyline of the path's
/// positions (a single sample: its point), where it is below `reach`, and,
/// when asked for, the nearest point of the path. Each segment measures only
/// the voxels within reach of it, so a long path costs its length, not the
/// box's voxels times its segments.
class PathDistance {
 public:
  /// The path (at least one sample) is kept by reference. `nearest_points`:
  /// closest() will be asked (the pinch), so each voxel's nearest segment is
  /// kept too (four bytes a voxel the other brushes do not fill).
  PathDistance(std::span<const StrokeSample> path, const Box& box, float reach,
               bool nearest_points = false);
  /// Distance from voxel v of the box to the path; infinity where no part
  /// of the path comes within reach.
  float at(glm::ivec3 v) const;
  /// Row (y, z) of the box's distances (relative to its corner): box().size().x
  /// floats, as at() gives them.
  const float* row(int y, int z) const;
  /// The path's nearest point to v (v within reach; nearest_points asked).
  glm::vec3 closest(glm::ivec3 v) const;

 private:
  std::span<const StrokeSample> path_;
  Box box_;
  DenseGrid<float> distance_;
  // The nearest segment, ending at that sample (0: the first point); empty
  // unless nearest_points.
  DenseGrid<int32_t> segment_;
};

/// A box holding every voxel within `reach` of the path's positions (not
/// clipped).
Box path_box(std::span<const StrokeSample> path, float reach);

/// The voxels of `volume` the ball swept through `path` can change: path_box()
/// of the ball's reach, clipped to the volume.
Box reach_box(const Volume& volume, std::span<const StrokeSample> path, const Ball& ball);

/// `passes` rounds of the separable [1 2 1] / 4 filter along x, y, z over g
/// (edges clamped): a binomial blur of variance passes / 2 voxel^2 per axis
/// that keeps the sum away from the edges.
void blur(DenseGrid<float>& g, int passes);

/// The material of `box` (grown by `margin` voxels, clipped to the volume)
/// as it is now, as floats 0..255.
class Field {
 public:
  Field(const Volume& volume, const Box& box, int margin);
  const Box& box() const { return box_; }
  const DenseGrid<float>& grid() const { return grid_; }
  DenseGrid<float>& grid() { return grid_; }
  /// The value at voxel v (inside box()).
  float at(glm::ivec3 v) const;
  /// Trilinear value at p (material voxel coordinates, clamped onto box()).
  float sample(glm::vec3 p) const;
  /// The density's gradient at p (per voxel; points into the material).
  glm::vec3 gradient(glm::vec3 p) const;

 private:
  Box box_;
  DenseGrid<float> grid_;
};

/// The plane fitted to the surface under the ball swept through `path`:
/// normal the weighted mean of the outward density gradient (-grad rho, so
/// each voxel counts by how much surface crosses it), through the weighted
/// centroid of those voxels. false when no surface lies under the ball.
struct Plane {
  glm::vec3 point{0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  /// Signed distance of p, positive on the outer side (voxels).
  float distance(glm::vec3 p) const;
  /// The density of the material filling the inner side at v: a hard tool
  /// rim's 2-voxel ramp (tool_density() of the distance, hardness 1).
  float density(glm::ivec3 v) const;
};
bool fit_plane(const Field& field, std::span<const StrokeSample> path, const Ball& ball,
               Plane& plane);

/// Writes, for every voxel of `region` the ball swept through `path` weighs
/// (weight w > 0; `path`: its distances, whose closest() is the path's
/// nearest point), round(value(v, w, path))
/// clamped to 0..255, as one undo step of `sculptor` (its volume is
/// `volume`, asserted). `before` holds region's material before the stroke;
/// the voxels not weighed are written back from it, whatever `volume` holds
/// there. `value` is called for slices of the region on every core at
/// once: it must only read. Returns the voxels changed from `before` (0:
/// nothing written, no undo step).
int64_t write(Volume& volume, Sculptor& sculptor, const Field& before, const Box& region,
              std::span<const StrokeSample> path, const Ball& ball,
              const std::function<float(glm::ivec3 v, float w, const PathDistance& path)>& value);
/// The same with the path's distances over `region` (to the ball's reach)
/// given.
int64_t write(Volume& volume, Sculptor& sculptor, const Field& before, const Box& region,
              const PathDistance& distance, const Ball& ball,
              const std::function<float(glm::ivec3 v, float w, const PathDistance& path)>& value);

/// Runs `a` and `b`, side by side when default_threads() allows (the calling
/// thread and one of the pool's), else one after the other: for a brush's
/// material and its path's distances, which do not depend on each other.
void side_by_side(const std::function<void()>& a, const std::function<void()>& b);

}  // namespace sculpt::core::brush
