#include "sculpt/core/volume/material_bounds.h"

#include <vector>

namespace sculpt::core {
namespace {

bool contains(const Box& outer, const Box& inner) {
  return glm::all(glm::lessThanEqual(outer.lo, inner.lo)) &&
         glm::all(glm::greaterThanEqual(outer.hi, inner.hi));
}

void include(Box& bounds, const Box& box) {
  bounds.lo = glm::min(bounds.lo, box.lo);
  bounds.hi = glm::max(bounds.hi, box.hi);
}

}  // namespace

std::optional<Box> material_bounds(const Volume& volume) {
  const glm::ivec3 grid = volume.brick_grid();
  Box bounds{volume.dims(), glm::ivec3(0)};  // empty until something is included
  std::vector<glm::ivec3> detailed;
  for (int64_t i = 0; i < volume.brick_count(); ++i) {
    const glm::ivec3 b = grid_position(i, grid);
    const Brick& brick = volume.brick(b);
    if (!brick.is_uniform()) {
      detailed.push_back(b);
    } else if (brick.uniform_value() > 0) {
      include(bounds, volume.brick_box(b));
    }
  }
  const int e = volume.brick_edge();
  std::vector<uint8_t> voxels(static_cast<size_t>(e) * e * e);
  for (glm::ivec3 b : detailed) {
    const Box box = volume.brick_box(b);
    if (!bounds.empty() && contains(bounds, box)) continue;
    volume.decode_brick(b, voxels);
    const glm::ivec3 size = box.size();
    for (int z = 0; z < size.z; ++z)
      for (int y = 0; y < size.y; ++y)
        for (int x = 0; x < size.x; ++x) {
          if (voxels[(static_cast<size_t>(z) * e + y) * e + x] == 0) continue;
          const glm::ivec3 p = box.lo + glm::ivec3(x, y, z);
          include(bounds, Box{p, p + 1});
        }
  }
  if (bounds.empty()) return std::nullopt;
  return bounds;
}

}  // namespace sculpt::core
