#include "sculpt/core/distance/distance_shell.h"
#include "sculpt/core/grid/grid_index.h"

#include <cmath>

#include <glm/common.hpp>

#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

// Sets `out` to v (where it is 0) at each voxel within the 3x3x3 cube
// around a voxel of `in` equal to `from`. The cube is separable: a 3-wide
// running "any" along x, then y, then z, each per z-slice or per row in
// parallel.
void dilate26(const DenseGrid<uint8_t>& in, uint8_t from, DenseGrid<uint8_t>& out, uint8_t v,
              int threads) {
  const glm::ivec3 d = in.dims();
  DenseGrid<uint8_t> a(d, 0), b(d, 0);
  const size_t sx = 1, sy = size_t(d.x), sz = size_t(d.x) * d.y;
  parallel_for(
      d.z,
      [&](int64_t z) {
        for (int y = 0; y < d.y; ++y) {
          const size_t r = size_t(z) * sz + size_t(y) * sy;
          for (int x = 0; x < d.x; ++x) {
            const bool hit = in[r + x] == from || (x > 0 && in[r + x - sx] == from) ||
                             (x + 1 < d.x && in[r + x + sx] == from);
            a[r + x] = hit;
          }
        }
        for (int y = 0; y < d.y; ++y) {
          const size_t r = size_t(z) * sz + size_t(y) * sy;
          for (int x = 0; x < d.x; ++x)
            b[r + x] = a[r + x] | (y > 0 ? a[r + x - sy] : 0) | (y + 1 < d.y ? a[r + x + sy] : 0);
        }
      },
      threads);
  parallel_for(
      d.z,
      [&](int64_t z) {
        for (size_t i = size_t(z) * sz; i < size_t(z + 1) * sz; ++i) {
          const bool hit = b[i] | (z > 0 ? b[i - sz] : 0) | (z + 1 < d.z ? b[i + sz] : 0);
          if (hit && out[i] == 0) out[i] = v;
        }
      },
      threads);
}

}  // namespace

DenseGrid<uint8_t> boundary_voxels(const DenseGrid<uint8_t>& inside, int threads) {
  const glm::ivec3 d = inside.dims();
  DenseGrid<uint8_t> b(d, 0);
  parallel_for(
      d.z,
      [&](int64_t zz) {
        const int z = int(zz);
        for (int y = 0; y < d.y; ++y)
          for (int x = 0; x < d.x; ++x) {
            if (inside.at(x, y, z) == 0) continue;
            bool outside_neighbour = false;
            for (int dz = -1; dz <= 1 && !outside_neighbour; ++dz)
              for (int dy = -1; dy <= 1 && !outside_neighbour; ++dy)
                for (int dx = -1; dx <= 1 && !outside_neighbour; ++dx) {
                  const int a = x + dx, c = y + dy, e = z + dz;
                  outside_neighbour = inside.in_bounds(a, c, e) && inside.at(a, c, e) == 0;
                }
            b.at(x, y, z) = outside_neighbour ? 1 : 0;
          }
      },
      threads);
  return b;
}

DistanceShell distance_shell(const DenseGrid<float>& phi, const SurfaceIndex& surface,
                             int threads) {
  const glm::ivec3 d = phi.dims();
  const DenseGrid<uint8_t> inside = inside_mask(phi);
  const DenseGrid<uint8_t> b = boundary_voxels(inside, threads);
  DistanceShell shell;
  // S_v: B dilated once; S_n: S_v dilated once more.
  DenseGrid<uint8_t> sv(d, 0);
  dilate26(b, 1, sv, DistanceShell::kInner, threads);
  shell.membership = sv;
  dilate26(sv, DistanceShell::kInner, shell.membership, DistanceShell::kOuter, threads);
  shell.slot = DenseGrid<int32_t>(d, -1);
  for (size_t i = 0; i < shell.membership.size(); ++i) {
    if (shell.membership[i] == DistanceShell::kNone) continue;
    shell.slot[i] = int32_t(shell.voxels.size());
    shell.voxels.push_back(int32_t(i));
  }
  shell.closest.resize(shell.voxels.size());
  shell.distance.resize(shell.voxels.size());
  shell.triangle.resize(shell.voxels.size());
  const int64_t n = int64_t(shell.voxels.size());
  const int64_t chunk = 1024;
  parallel_for((n + chunk - 1) / chunk,
               [&](int64_t c) {
                 for (int64_t k = c * chunk; k < std::min(n, (c + 1) * chunk); ++k) {
                   const int32_t i = shell.voxels[k];
                   const SurfaceIndex::Nearest near = surface.nearest(grid_position(i, d));
                   const float dist = std::sqrt(near.distance_squared);
                   shell.closest[k] = near.point;
                   shell.triangle[k] = near.triangle;
                   shell.distance[k] = inside[i] ? -dist : dist;
                 }
               },
               threads);
  return shell;
}

}  // namespace sculpt::core
