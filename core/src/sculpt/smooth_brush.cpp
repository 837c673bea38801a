// Smoothing by blending toward a blur of the density, not by moving mesh
// vertices: the material is the density volume, and a binomial blur of it
// keeps its sum exactly (away from the volume's border), so what the brush
// takes from bumps it gives to dents. The per-stroke weight is the swept
// ball's largest filling, as a SweptStroke's, so slow and fast strokes
// smooth alike.

#include "sculpt/core/sculpt/smooth_brush.h"

#include <cassert>
#include <optional>

#include "brush_field.h"

namespace sculpt::core {

Status check_smooth_brush(const SmoothBrushOptions& o) {
  if (Status st = brush::check_ball({o.radius_vox, o.hardness, o.strength}); !st) return st;
  if (!(o.passes >= 1 && o.passes <= kMaxSmoothPasses))
    return Error("'passes' must be a whole number in [1, " + std::to_string(kMaxSmoothPasses) +
                 "], got " + std::to_string(o.passes));
  return {};
}

int64_t smooth_stroke(Volume& volume, Sculptor& sculptor, std::span<const StrokeSample> path,
                      const SmoothBrushOptions& o) {
  return smooth_stroke_part(volume, sculptor, path, o, Box{glm::ivec3(0), volume.dims()}, volume);
}

int64_t smooth_stroke_part(Volume& volume, Sculptor& sculptor, std::span<const StrokeSample> path,
                           const SmoothBrushOptions& o, const Box& part, const Volume& before) {
  assert(!path.empty() && check_smooth_brush(o) && before.dims() == volume.dims());
  const brush::Ball ball{o.radius_vox, o.hardness, o.strength};
  const Box region = intersect(brush::reach_box(volume, path, ball), part);
  if (region.empty()) return 0;
  // The blur reads `passes` voxels around each voxel it writes: the same
  // values, with the same rounding, however far the field reaches beyond.
  // It and the path's distances, independent, are made side by side.
  std::optional<brush::Field> material, blurred;
  std::optional<brush::PathDistance> distance;
  brush::side_by_side(
      [&] {
        material.emplace(before, region, o.passes);
        blurred.emplace(*material);
        brush::blur(blurred->grid(), o.passes);
      },
      [&] { distance.emplace(path, region, ball.reach()); });
  return brush::write(volume, sculptor, *material, region, *distance, ball,
                      [&](glm::ivec3 v, float w, const brush::PathDistance&) {
                        const float m = material->at(v);
                        return m + w * (blurred->at(v) - m);
                      });
}

}  // namespace sculpt::core
