#include "sculpt/core/distance/surface_index.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "sculpt/core/mesh/point_triangle.h"
#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {

SurfaceIndex::SurfaceIndex(const DenseGrid<float>& phi, int threads) {
  const glm::ivec3 d = phi.dims();
  cell_dims_ = glm::max(d - 1, glm::ivec3(0));
  first_ = DenseGrid<int32_t>(cell_dims_, 0);
  count_ = DenseGrid<uint8_t>(cell_dims_, 0);
  if (voxel_count(cell_dims_) == 0) return;
  // Per slab of cells in parallel, then joined in z order (deterministic).
  std::vector<std::vector<Triangle3>> slabs(cell_dims_.z);
  parallel_for(
      cell_dims_.z,
      [&](int64_t z) {
        std::array<Triangle3, kMaxCellTriangles> buf;
        auto& out = slabs[z];
        for (int y = 0; y < cell_dims_.y; ++y)
          for (int x = 0; x < cell_dims_.x; ++x) {
            const int n = cell_triangles(phi, {x, y, int(z)}, buf);
            count_.at(x, y, int(z)) = uint8_t(n);
            out.insert(out.end(), buf.begin(), buf.begin() + n);
          }
      },
      threads);
  size_t total = 0;
  for (const auto& s : slabs)
    total += s.size();
  triangles_.reserve(total);
  bounds_.reserve(total);
  int32_t next = 0;
  for (int z = 0; z < cell_dims_.z; ++z) {
    triangles_.insert(triangles_.end(), slabs[z].begin(), slabs[z].end());
    for (const Triangle3& t : slabs[z]) {
      const glm::vec3 c = (t.a + t.b + t.c) / 3.0f;
      const float r = std::sqrt(std::max(
          {glm::dot(t.a - c, t.a - c), glm::dot(t.b - c, t.b - c), glm::dot(t.c - c, t.c - c)}));
      bounds_.emplace_back(c, r);
    }
    for (int y = 0; y < cell_dims_.y; ++y)
      for (int x = 0; x < cell_dims_.x; ++x) {
        const size_t i = first_.index(x, y, z);
        first_[i] = next;
        next += count_[i];
      }
  }
}

SurfaceIndex::Nearest SurfaceIndex::nearest(glm::ivec3 p, int max_radius) const {
  Nearest best{glm::vec3(0.0f), std::numeric_limits<float>::infinity()};
  const glm::vec3 pf(p);
  float best_dist = std::numeric_limits<float>::infinity();
  // Ring r: cells with lower corner in [p - r, p + r - 1] but not in ring
  // r - 1. Every point of such a cell is at least r - 1 voxels from p.
  for (int r = 1; r <= max_radius; ++r) {
    const float min_dist = float(r - 1);
    if (best.distance_squared <= min_dist * min_dist) break;
    const glm::ivec3 lo = glm::max(p - r, glm::ivec3(0));
    const glm::ivec3 hi = glm::min(p + r - 1, cell_dims_ - 1);
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
          const int ring =
              std::max({x < p.x ? p.x - x : x - p.x + 1, y < p.y ? p.y - y : y - p.y + 1,
                        z < p.z ? p.z - z : z - p.z + 1});
          if (ring != r) {
            // Inside the ring on every axis: jump over the inner run of x.
            if (x < p.x + r - 2) x = p.x + r - 2;
            continue;
          }
          const size_t i = first_.index(x, y, z);
          const uint8_t n = count_[i];
          if (n == 0) continue;
          // A cell's box farther than the best point so far cannot help;
          // this keeps the search to the ball of the answer's radius.
          const glm::vec3 corner{float(x), float(y), float(z)};
          if (point_box_distance_squared(pf, corner, corner + 1.0f) >= best.distance_squared)
            continue;
          const Triangle3* t = triangles_.data() + first_[i];
          const glm::vec4* ball = bounds_.data() + first_[i];
          for (uint8_t k = 0; k < n; ++k) {
            const glm::vec3 dc = pf - glm::vec3(ball[k]);
            const float reach = best_dist + ball[k].w;
            if (glm::dot(dc, dc) >= reach * reach) continue;
            const ClosestPoint c = closest_point_on_triangle(pf, t[k].a, t[k].b, t[k].c);
            if (c.distance_squared < best.distance_squared) {
              best.distance_squared = c.distance_squared;
              best.point = c.point;
              best.triangle = int32_t(first_[i] + k);
              best_dist = std::sqrt(c.distance_squared);
            }
          }
        }
  }
  return best;
}

SurfaceIndex::Nearest SurfaceIndex::nearest_in_cells(glm::vec3 p, glm::ivec3 lo, glm::ivec3 hi,
                                                     Nearest best) const {
  lo = glm::max(lo, glm::ivec3(0));
  hi = glm::min(hi, cell_dims_ - 1);
  float best_dist = std::sqrt(best.distance_squared);
  int32_t found = -1;  // a triangle nearer than `best`
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y)
      for (int x = lo.x; x <= hi.x; ++x) {
        const size_t i = first_.index(x, y, z);
        const uint8_t n = count_[i];
        if (n == 0) continue;
        const glm::vec3 corner{float(x), float(y), float(z)};
        if (point_box_distance_squared(p, corner, corner + 1.0f) >= best.distance_squared) continue;
        const Triangle3* t = triangles_.data() + first_[i];
        const glm::vec4* ball = bounds_.data() + first_[i];
        for (uint8_t k = 0; k < n; ++k) {
          const glm::vec3 dc = p - glm::vec3(ball[k]);
          const float reach = best_dist + ball[k].w;
          if (glm::dot(dc, dc) >= reach * reach) continue;
          // Distance only here; the point once, for the winner.
          const float d2 = triangle_distance2(p, t[k].a, t[k].b - t[k].a, t[k].c - t[k].a);
          if (d2 < best.distance_squared) {
            best.distance_squared = d2;
            best_dist = std::sqrt(d2);
            found = int32_t(first_[i] + k);
          }
        }
      }
  if (found >= 0) {
    const Triangle3& t = triangles_[size_t(found)];
    best.point = closest_point_on_triangle(p, t.a, t.b, t.c).point;
    best.triangle = found;
  }
  return best;
}

}  // namespace sculpt::core
