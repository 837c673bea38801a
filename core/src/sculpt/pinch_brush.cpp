// Pinch as a radial contraction toward the path's line, sampled backwards
// (each voxel reads where its material comes from), so every voxel is
// written once from the material as it was and none is left unfilled.

#include "sculpt/core/sculpt/pinch_brush.h"

#include <cassert>
#include <cmath>
#include <optional>

#include "brush_field.h"

namespace sculpt::core {

Status check_pinch_brush(const PinchBrushOptions& o) {
  return brush::check_ball({o.radius_vox, o.hardness, o.strength});
}

int pinch_read_margin(const PinchBrushOptions& o) {
  // A voxel at the reach reads up to twice as far from the path.
  const brush::Ball ball{o.radius_vox, o.hardness, o.strength};
  return static_cast<int>(std::ceil(ball.reach())) + 2;
}

int64_t pinch_stroke(Volume& volume, Sculptor& sculptor, std::span<const StrokeSample> path,
                     const PinchBrushOptions& o) {
  return pinch_stroke_part(volume, sculptor, path, o, Box{glm::ivec3(0), volume.dims()}, volume);
}

int64_t pinch_stroke_part(Volume& volume, Sculptor& sculptor, std::span<const StrokeSample> path,
                          const PinchBrushOptions& o, const Box& part, const Volume& before) {
  assert(!path.empty() && check_pinch_brush(o) && before.dims() == volume.dims());
  const brush::Ball ball{o.radius_vox, o.hardness, o.strength};
  const Box region = intersect(brush::reach_box(volume, path, ball), part);
  if (region.empty()) return 0;
  // The material and the path's distances, independent, side by side.
  std::optional<brush::Field> material;
  std::optional<brush::PathDistance> distance;
  brush::side_by_side(
      [&] { material.emplace(before, region, pinch_read_margin(o)); },
      [&] { distance.emplace(path, region, ball.reach(), /*nearest_points=*/true); });
  return brush::write(volume, sculptor, *material, region, *distance, ball,
                      [&](glm::ivec3 v, float w, const brush::PathDistance& path_distance) {
                        const glm::vec3 c = path_distance.closest(v);
                        return material->sample(c + (1.0f + w) * (glm::vec3(v) - c));
                      });
}

}  // namespace sculpt::core
