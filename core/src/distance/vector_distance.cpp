#include "sculpt/core/distance/vector_distance.h"
#include "sculpt/core/grid/grid_index.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace sculpt::core {
namespace {

// "No surface known yet": far enough that any real vector wins, small
// enough that adding offsets and squaring stays finite in float.
constexpr float kFar = 1e7f;

struct Grid {
  glm::ivec3 pd;
  std::vector<glm::vec3> v;
  std::vector<float> len2;
  size_t index(int x, int y, int z) const { return (size_t(z) * pd.y + y) * pd.x + x; }
  std::ptrdiff_t offset(int dx, int dy, int dz) const {
    return (std::ptrdiff_t(dz) * pd.y + dy) * pd.x + dx;
  }
};

}  // namespace

DenseGrid<float> vector_distance(glm::ivec3 dims, const std::vector<VectorSeed>& seeds,
                                 VectorScheme scheme) {
  Grid g;
  g.pd = dims + 2;  // one voxel of padding that never holds a surface
  const size_t n = size_t(voxel_count(g.pd));
  g.v.assign(n, glm::vec3(kFar));
  g.len2.assign(n, 3.0f * kFar * kFar);
  for (const VectorSeed& s : seeds) {
    const glm::ivec3 v = grid_position(s.voxel, dims);
    const size_t p = g.index(v.x + 1, v.y + 1, v.z + 1);
    g.v[p] = s.to_surface;
    g.len2[p] = glm::dot(s.to_surface, s.to_surface);
  }
  // Takes the neighbour at offset o = q - p when its vector, moved to p, is shorter.
  auto take = [&](size_t p, int dx, int dy, int dz) {
    const size_t q = size_t(std::ptrdiff_t(p) + g.offset(dx, dy, dz));
    const glm::vec3 c = g.v[q] + glm::vec3(float(dx), float(dy), float(dz));
    const float l = glm::dot(c, c);
    if (l < g.len2[p]) {
      g.v[p] = c;
      g.len2[p] = l;
    }
  };
  if (scheme == VectorScheme::kVcvdt) {
    for (int sz = -1; sz <= 1; sz += 2)
      for (int sy = -1; sy <= 1; sy += 2)
        for (int sx = -1; sx <= 1; sx += 2) {
          for (int zi = 0; zi < dims.z; ++zi) {
            const int z = sz > 0 ? zi + 1 : dims.z - zi;
            for (int yi = 0; yi < dims.y; ++yi) {
              const int y = sy > 0 ? yi + 1 : dims.y - yi;
              for (int xi = 0; xi < dims.x; ++xi) {
                const int x = sx > 0 ? xi + 1 : dims.x - xi;
                const size_t p = g.index(x, y, z);
                take(p, -sx, 0, 0);
                take(p, 0, -sy, 0);
                take(p, 0, 0, -sz);
              }
            }
          }
        }
  } else {
    for (int s = 1; s >= -1; s -= 2) {  // forward, then backward
      for (int zi = 0; zi < dims.z; ++zi) {
        const int z = s > 0 ? zi + 1 : dims.z - zi;
        for (int yi = 0; yi < dims.y; ++yi) {
          const int y = s > 0 ? yi + 1 : dims.y - yi;
          for (int xi = 0; xi < dims.x; ++xi) {
            const int x = s > 0 ? xi + 1 : dims.x - xi;
            const size_t p = g.index(x, y, z);
            // The 13 neighbours visited before p in this pass's order.
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx)
                take(p, s * dx, s * dy, -s);
            for (int dx = -1; dx <= 1; ++dx)
              take(p, s * dx, -s, 0);
            take(p, -s, 0, 0);
          }
          for (int xi = dims.x - 1; xi >= 0; --xi) {
            const int x = s > 0 ? xi + 1 : dims.x - xi;
            take(g.index(x, y, z), s, 0, 0);
          }
        }
      }
    }
  }
  DenseGrid<float> out(dims);
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x)
        out.at(x, y, z) = std::sqrt(g.len2[g.index(x + 1, y + 1, z + 1)]);
  return out;
}

}  // namespace sculpt::core
