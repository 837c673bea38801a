#include "sculpt/core/tool/tool_scale.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <glm/common.hpp>

namespace sculpt::core {
namespace {

// Density of `grid` at point p (voxel centres at integers), trilinear; 0
// outside the grid.
float trilinear(const DenseGrid<uint8_t>& grid, glm::vec3 p) {
  const glm::ivec3 d = grid.dims();
  const glm::vec3 f = glm::floor(p);
  const glm::ivec3 i0(f);
  const glm::vec3 t = p - f;
  float sum = 0.0f;
  for (int c = 0; c < 8; ++c) {
    const glm::ivec3 o(c & 1, (c >> 1) & 1, (c >> 2) & 1);
    const glm::ivec3 q = i0 + o;
    if (glm::any(glm::lessThan(q, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(q, d)))
      continue;
    const float w = (o.x ? t.x : 1.0f - t.x) * (o.y ? t.y : 1.0f - t.y) * (o.z ? t.z : 1.0f - t.z);
    sum += w * static_cast<float>(grid.at(q.x, q.y, q.z));
  }
  return sum;
}

}  // namespace

glm::ivec3 scaled_tool_dims(glm::ivec3 dims, float factor) {
  return glm::max(glm::ivec3(glm::round(glm::vec3(dims) * factor)), glm::ivec3(1));
}

Tool scale_tool(const Tool& tool, float factor) {
  assert(factor >= kMinToolScale && factor <= kMaxToolScale);
  const glm::ivec3 in = tool.density.dims();
  const glm::ivec3 out = scaled_tool_dims(in, factor);
  // Voxel q covers [q - 0.5, q + 0.5]; the grid's box [-0.5, dims - 0.5]
  // scales to [-0.5, out - 0.5], so q's centre came from (q + 0.5) / s - 0.5
  // with s the factor the grid really took per axis (rounding dims).
  const glm::vec3 s = glm::vec3(out) / glm::vec3(in);
  Tool scaled;
  scaled.density = DenseGrid<uint8_t>(out);
  for (int z = 0; z < out.z; ++z)
    for (int y = 0; y < out.y; ++y)
      for (int x = 0; x < out.x; ++x) {
        const glm::vec3 p = (glm::vec3(x, y, z) + 0.5f) / s - 0.5f;
        scaled.density.at(x, y, z) =
            static_cast<uint8_t>(std::clamp(std::lround(trilinear(tool.density, p)), 0L, 255L));
      }
  scaled.pivot = (tool.pivot + 0.5f) * s - 0.5f;
  scaled.hardness = tool.hardness;
  return scaled;
}

}  // namespace sculpt::core
