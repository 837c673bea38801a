// Flatten toward one plane fitted to the whole stroke, not a plane per dab:
// the stroke is applied at once (as a SweptStroke's strength, once), so a
// plane per position would have no meaning, and one plane makes a long
// stroke a flat facet, as a sculptor planing a surface expects.

#include "sculpt/core/sculpt/flatten_brush.h"

#include <cassert>

#include "brush_field.h"

namespace sculpt::core {

Status check_flatten_brush(const FlattenBrushOptions& o) {
  return brush::check_ball({o.radius_vox, o.hardness, o.strength});
}

int64_t flatten_stroke(Volume& volume, Sculptor& sculptor, std::span<const StrokeSample> path,
                       const FlattenBrushOptions& o) {
  assert(!path.empty() && check_flatten_brush(o));
  const brush::Ball ball{o.radius_vox, o.hardness, o.strength};
  const Box region = brush::reach_box(volume, path, ball);
  if (region.empty()) return 0;
  const brush::Field before(volume, region, 1);
  brush::Plane plane;
  if (!brush::fit_plane(before, path, ball, plane)) return 0;
  return brush::write(volume, sculptor, before, region, path, ball,
                      [&](glm::ivec3 v, float w, const brush::PathDistance&) {
                        const float m = before.at(v);
                        const float p = plane.density(v);
                        return m + w * (p - m);
                      });
}

}  // namespace sculpt::core
