// Inflate as a dilation of the density (sample it inward along the normal)
// rather than moving mesh vertices: the material is the density, and a
// dilation keeps its ramp, so the surface stays antialiased. The normal
// comes from a blurred copy because the density's own gradient vanishes a
// voxel away from the surface, and a voxel up to distance_vox + 1 outside
// must know which way the surface lies.

#include "sculpt/core/sculpt/inflate_brush.h"

#include <cassert>
#include <cmath>

#include <glm/geometric.hpp>

#include "brush_field.h"

namespace sculpt::core {

Status check_inflate_brush(const InflateBrushOptions& o) {
  if (Status st = brush::check_ball({o.radius_vox, o.hardness, o.strength}); !st) return st;
  return brush::check_positive("distance", o.distance_vox, kMaxInflateDistanceVox);
}

int64_t inflate_stroke(Volume& volume, Sculptor& sculptor, std::span<const StrokeSample> path,
                       const InflateBrushOptions& o) {
  assert(!path.empty() && check_inflate_brush(o));
  const brush::Ball ball{o.radius_vox, o.hardness, o.strength};
  const Box region = brush::reach_box(volume, path, ball);
  if (region.empty()) return 0;
  // Each blur round spreads the gradient a voxel farther from the surface.
  const int passes = static_cast<int>(std::ceil(o.distance_vox)) + 1;
  const int margin = static_cast<int>(std::ceil(o.distance_vox)) + passes + 2;
  const brush::Field before(volume, region, margin);
  brush::Field blurred = before;
  brush::blur(blurred.grid(), passes);
  return brush::write(volume, sculptor, before, region, path, ball,
                      [&](glm::ivec3 v, float w, glm::vec3) {
                        const glm::vec3 p(v);
                        const glm::vec3 g = blurred.gradient(p);
                        const float len = glm::length(g);
                        if (len <= 1e-3f) return before.at(v);
                        // The gradient points inward: the sample lies inward.
                        return before.sample(p + g / len * (w * o.distance_vox));
                      });
}

}  // namespace sculpt::core
