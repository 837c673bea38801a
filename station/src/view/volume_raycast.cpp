#include "sculpt/station/view/volume_raycast.h"

#include <algorithm>
#include <cmath>

namespace sculpt::station {
namespace {

constexpr float kStep = 0.5f;  // voxels: no surface thicker than a voxel is skipped
constexpr int kRefinements = 3;

// Nearest voxel's density (0 outside the block).
float density_at(const core::Volume& v, glm::vec3 p) {
  const glm::ivec3 i(glm::floor(p + 0.5f));
  if (glm::any(glm::lessThan(i, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(i, v.dims())))
    return 0.0f;
  return v.voxel(i);
}

}  // namespace

std::optional<glm::vec3> raycast_surface(const core::Volume& volume, const Ray& ray, float iso) {
  // Clip the ray to the block (slab method).
  const glm::vec3 lo(-0.5f), hi = glm::vec3(volume.dims()) - 0.5f;
  float t0 = 0.0f, t1 = 1e9f;
  for (int a = 0; a < 3; ++a) {
    const float d = ray.direction[a];
    if (std::abs(d) < 1e-12f) {
      if (ray.origin[a] < lo[a] || ray.origin[a] > hi[a]) return std::nullopt;
      continue;
    }
    float ta = (lo[a] - ray.origin[a]) / d, tb = (hi[a] - ray.origin[a]) / d;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (t0 > t1) return std::nullopt;
  float previous = t0;
  for (float t = t0; t <= t1; t += kStep) {
    if (density_at(volume, ray.origin + t * ray.direction) > iso) {
      // Halve the step a few times between the last outside and this inside point.
      float out = previous, in = t;
      for (int k = 0; k < kRefinements; ++k) {
        const float mid = 0.5f * (out + in);
        (density_at(volume, ray.origin + mid * ray.direction) > iso ? in : out) = mid;
      }
      return ray.origin + in * ray.direction;
    }
    previous = t;
  }
  return std::nullopt;
}

}  // namespace sculpt::station
