// Inflate as a dilation of the density (sample it inward along the normal)
// rather than moving mesh vertices: the material is the density, and a
// dilation keeps its ramp, so the surface stays antialiased. The normal
// comes from a blurred copy because the density's own gradient vanishes a
// voxel away from the surface, and a voxel up to distance_vox + 1 outside
// must know which way the surface lies.

#include "sculpt/core/sculpt/inflate_brush.h"

#include <cassert>
#include <cmath>
#include <optional>

#include <glm/geometric.hpp>

#include "brush_field.h"

namespace sculpt::core {

Status check_inflate_brush(const InflateBrushOptions& o) {
  if (Status st = brush::check_ball({o.radius_vox, o.hardness, o.strength}); !st) return st;
  return brush::check_positive("distance", o.distance_vox, kMaxInflateDistanceVox);
}

namespace {

// Each blur round spreads the gradient a voxel farther from the surface.
int blur_passes(const InflateBrushOptions& o) {
  return static_cast<int>(std::ceil(o.distance_vox)) + 1;
}

}  // namespace

int inflate_read_margin(const InflateBrushOptions& o) {
  // The blur reads its passes around the gradient's voxels, a voxel beyond
  // the sample, which lies up to distance_vox inward.
  return static_cast<int>(std::ceil(o.distance_vox)) + blur_passes(o) + 2;
}

int64_t inflate_stroke(Volume& volume, Sculptor& sculptor, std::span<const StrokeSample> path,
                       const InflateBrushOptions& o) {
  return inflate_stroke_part(volume, sculptor, path, o, Box{glm::ivec3(0), volume.dims()}, volume);
}

int64_t inflate_stroke_part(Volume& volume, Sculptor& sculptor, std::span<const StrokeSample> path,
                            const InflateBrushOptions& o, const Box& part, const Volume& before) {
  assert(!path.empty() && check_inflate_brush(o) && before.dims() == volume.dims());
  const brush::Ball ball{o.radius_vox, o.hardness, o.strength};
  const Box region = intersect(brush::reach_box(volume, path, ball), part);
  if (region.empty()) return 0;
  // The blurred material and the path's distances, independent, side by side.
  std::optional<brush::Field> material, blurred;
  std::optional<brush::PathDistance> distance;
  brush::side_by_side(
      [&] {
        material.emplace(before, region, inflate_read_margin(o));
        blurred.emplace(*material);
        brush::blur(blurred->grid(), blur_passes(o));
      },
      [&] { distance.emplace(path, region, ball.reach()); });
  return brush::write(volume, sculptor, *material, region, *distance, ball,
                      [&](glm::ivec3 v, float w, const brush::PathDistance&) {
                        const glm::vec3 p(v);
                        const glm::vec3 g = blurred->gradient(p);
                        const float len = glm::length(g);
                        if (len <= 1e-3f) return material->at(v);
                        // The gradient points inward: the sample lies inward.
                        return material->sample(p + g / len * (w * o.distance_vox));
                      });
}

}  // namespace sculpt::core
