// Pinch as a radial contraction toward the path's line, sampled backwards
// (each voxel reads where its material comes from), so every voxel is
// written once from the material as it was and none is left unfilled.

#include "sculpt/core/sculpt/pinch_brush.h"

#include <cassert>
#include <cmath>

#include "brush_field.h"

namespace sculpt::core {

Status check_pinch_brush(const PinchBrushOptions& o) {
  return brush::check_ball({o.radius_vox, o.hardness, o.strength});
}

int64_t pinch_stroke(Volume& volume, Sculptor& sculptor, std::span<const StrokeSample> path,
                     const PinchBrushOptions& o) {
  assert(!path.empty() && check_pinch_brush(o));
  const brush::Ball ball{o.radius_vox, o.hardness, o.strength};
  const Box region = brush::reach_box(volume, path, ball);
  if (region.empty()) return 0;
  // A voxel at the reach reads up to twice as far from the path.
  const brush::Field before(volume, region, static_cast<int>(std::ceil(ball.reach())) + 2);
  return brush::write(volume, sculptor, before, region, path, ball,
                      [&](glm::ivec3 v, float w, glm::vec3 c) {
                        return before.sample(c + (1.0f + w) * (glm::vec3(v) - c));
                      });
}

}  // namespace sculpt::core
