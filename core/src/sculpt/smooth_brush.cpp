// Smoothing by blending toward a blur of the density, not by moving mesh
// vertices: the material is the density volume, and a binomial blur of it
// keeps its sum exactly (away from the volume's border), so what the brush
// takes from bumps it gives to dents. The per-stroke weight is the swept
// ball's largest filling, as a SweptStroke's, so slow and fast strokes
// smooth alike.

#include "sculpt/core/sculpt/smooth_brush.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace sculpt::core {
namespace {

float segment_distance(glm::vec3 p, glm::vec3 a, glm::vec3 b) {
  const glm::vec3 ab = b - a;
  const float ab2 = glm::dot(ab, ab);
  const float t = ab2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / ab2, 0.0f, 1.0f) : 0.0f;
  return glm::length(p - a - t * ab);
}

// One [1 2 1] / 4 pass along `axis` over g (dims d), edges clamped.
void blur_axis(std::vector<float>& g, glm::ivec3 d, int axis, std::vector<float>& tmp) {
  tmp = g;
  const int64_t stride = axis == 0 ? 1 : axis == 1 ? d.x : int64_t{d.x} * d.y;
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        const glm::ivec3 p(x, y, z);
        const int64_t i = (int64_t{z} * d.y + y) * d.x + x;
        const float prev = p[axis] > 0 ? tmp[static_cast<size_t>(i - stride)] : tmp[i];
        const float next = p[axis] + 1 < d[axis] ? tmp[static_cast<size_t>(i + stride)] : tmp[i];
        g[static_cast<size_t>(i)] =
            0.25f * prev + 0.5f * tmp[static_cast<size_t>(i)] + 0.25f * next;
      }
}

}  // namespace

int64_t smooth_stroke(Volume& volume, Sculptor& sculptor, std::span<const StrokeSample> path,
                      const SmoothBrushOptions& o) {
  assert(&sculptor.volume() == &volume);
  assert(!path.empty() && o.radius_vox > 0.0f && o.passes >= 1);
  assert(o.hardness >= 0.0f && o.hardness <= 1.0f && o.strength >= 0.0f && o.strength <= 1.0f);
  const float reach = o.radius_vox + 1.0f;
  glm::vec3 lo = path[0].position_vox, hi = lo;
  for (const StrokeSample& s : path) {
    lo = glm::min(lo, s.position_vox);
    hi = glm::max(hi, s.position_vox);
  }
  const Box vol{glm::ivec3(0), volume.dims()};
  const Box region = intersect(
      Box{glm::ivec3(glm::floor(lo - reach)), glm::ivec3(glm::ceil(hi + reach)) + 1}, vol);
  if (region.empty()) return 0;
  // The blur reads `passes` voxels around each voxel it writes.
  const Box read_box = intersect(Box{region.lo - o.passes, region.hi + o.passes}, vol);
  const DenseGrid<uint8_t> before = volume.read(read_box, 0);
  const glm::ivec3 d = read_box.size();
  std::vector<float> blur(before.values().begin(), before.values().end());
  std::vector<float> tmp;
  for (int k = 0; k < o.passes; ++k)
    for (int axis = 0; axis < 3; ++axis)
      blur_axis(blur, d, axis, tmp);

  DenseGrid<uint8_t> out = volume.read(region, 0);
  int64_t changed = 0;
  for (int z = region.lo.z; z < region.hi.z; ++z)
    for (int y = region.lo.y; y < region.hi.y; ++y)
      for (int x = region.lo.x; x < region.hi.x; ++x) {
        const glm::vec3 p(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
        float dist = glm::length(p - path[0].position_vox);
        for (size_t i = 1; i < path.size(); ++i)
          dist =
              std::min(dist, segment_distance(p, path[i - 1].position_vox, path[i].position_vox));
        if (dist >= reach) continue;
        const float w =
            o.strength * tool_density(dist - o.radius_vox, o.radius_vox, o.hardness) / 255.0f;
        const glm::ivec3 q = glm::ivec3(x, y, z) - read_box.lo;
        const size_t i = before.index(q.x, q.y, q.z);
        const float m = before[i];
        const float v = std::clamp(std::round(m + w * (blur[i] - m)), 0.0f, 255.0f);
        const auto r = static_cast<uint8_t>(v);
        changed += r != before[i];
        const glm::ivec3 o_at = glm::ivec3(x, y, z) - region.lo;
        out.at(o_at.x, o_at.y, o_at.z) = r;
      }
  if (changed == 0) return 0;
  sculptor.external_edit(region, [&] { volume.write(region.lo, out); });
  return changed;
}

}  // namespace sculpt::core
