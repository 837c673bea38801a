#pragma once
// Integer boxes in voxel index space (DESIGN.md §3: voxel centres at integer
// coordinates, x fastest in memory).

#include <algorithm>
#include <cstdint>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace sculpt::core {

/// Half-open box of voxel indices [lo, hi) on each axis.
struct Box {
  glm::ivec3 lo{0};
  glm::ivec3 hi{0};

  bool empty() const { return hi.x <= lo.x || hi.y <= lo.y || hi.z <= lo.z; }
  glm::ivec3 size() const { return glm::max(hi - lo, glm::ivec3(0)); }
  int64_t voxel_count() const {
    const glm::ivec3 s = size();
    return int64_t{s.x} * s.y * s.z;
  }
  bool contains(glm::ivec3 p) const {
    return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x < hi.x && p.y < hi.y && p.z < hi.z;
  }
  friend bool operator==(const Box&, const Box&) = default;
};

/// The overlap of two boxes; empty when they do not meet.
inline Box intersect(const Box& a, const Box& b) {
  return Box{glm::max(a.lo, b.lo), glm::min(a.hi, b.hi)};
}

/// The smallest box holding both; an empty box adds nothing.
inline Box hull(const Box& a, const Box& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  return Box{glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)};
}

/// Number of voxels in a grid of `dims`.
inline int64_t voxel_count(glm::ivec3 dims) {
  return int64_t{dims.x} * dims.y * dims.z;
}

}  // namespace sculpt::core
