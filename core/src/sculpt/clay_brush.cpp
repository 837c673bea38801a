// Clay as "fill up to a plane" rather than "add a layer of material": an
// add stroke builds on whatever is under it, so its top copies the bumps it
// covers; a plane caps the fill, so the top flattens and the next stroke,
// fitting its plane to this one's top, builds the next layer on it (the
// behaviour of Blender's Clay and ZBrush's Clay brushes).

#include "sculpt/core/sculpt/clay_brush.h"

#include <algorithm>
#include <cassert>

#include "brush_field.h"

namespace sculpt::core {

Status check_clay_brush(const ClayBrushOptions& o) {
  if (Status st = brush::check_ball({o.radius_vox, o.hardness, o.strength}); !st) return st;
  return brush::check_range("layer", o.layer, 0.0, 1.0);
}

int64_t clay_stroke(Volume& volume, Sculptor& sculptor, std::span<const StrokeSample> path,
                    const ClayBrushOptions& o) {
  assert(!path.empty() && check_clay_brush(o));
  const brush::Ball ball{o.radius_vox, o.hardness, o.strength};
  const Box region = brush::reach_box(volume, path, ball);
  if (region.empty()) return 0;
  // The gradient reads one voxel around each voxel of the fit.
  const brush::Field before(volume, region, 1);
  brush::Plane plane;
  if (!brush::fit_plane(before, path.first(1), ball, plane)) return 0;
  plane.point += plane.normal * (o.layer * o.radius_vox);
  return brush::write(volume, sculptor, before, region, path, ball,
                      [&](glm::ivec3 v, float w, const brush::PathDistance&) {
                        const float m = before.at(v);
                        const float p = plane.density(v);
                        return m + w * std::max(0.0f, p - m);
                      });
}

}  // namespace sculpt::core
