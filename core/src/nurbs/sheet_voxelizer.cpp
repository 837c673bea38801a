// Shell voxelisation by brute force over each brick's nearby triangles: the
// sheets the station builds have a few tens of thousands of triangles and a
// thin shell, so the per-brick triangle lists are short. (A distance-field
// module with faster transforms is being written separately; this file does
// not depend on it.)

#include "sculpt/core/nurbs/sheet_voxelizer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace sculpt::core::nurbs {

double point_triangle_distance(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  // Ericson §5.1.5: find the Voronoi region of p and its closest point.
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return glm::length(p - a);
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return glm::length(p - b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    return glm::length(p - (a + v * ab));
  }
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return glm::length(p - c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    return glm::length(p - (a + w * ac));
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return glm::length(p - (b + w * (c - b)));
  }
  const double denom = 1.0 / (va + vb + vc);
  if (!std::isfinite(denom)) {
    // Degenerate (zero-area) triangle: the closest of its three edges.
    auto seg = [&](glm::dvec3 s, glm::dvec3 e) {
      const glm::dvec3 d = e - s;
      const double len2 = glm::dot(d, d);
      const double t = len2 > 0.0 ? std::clamp(glm::dot(p - s, d) / len2, 0.0, 1.0) : 0.0;
      return glm::length(p - (s + t * d));
    };
    return std::min({seg(a, b), seg(b, c), seg(c, a)});
  }
  const double v = vb * denom, w = vc * denom;
  return glm::length(p - (a + ab * v + ac * w));
}

Box voxelize_shell(const Mesh& mesh, double thickness_vox, ShellMode mode, Volume& volume) {
  const double half = 0.5 * thickness_vox;
  const double reach = half + 0.5;  // beyond it the density is 0
  struct Tri {
    glm::dvec3 a, b, c;
    glm::ivec3 lo, hi;  // voxel box within reach, half-open
  };
  std::vector<Tri> tris;
  tris.reserve(mesh.triangles.size());
  Box all{glm::ivec3(std::numeric_limits<int>::max()), glm::ivec3(std::numeric_limits<int>::min())};
  for (const glm::uvec3& t : mesh.triangles) {
    Tri tri{glm::dvec3(mesh.positions[t.x]),
            glm::dvec3(mesh.positions[t.y]),
            glm::dvec3(mesh.positions[t.z]),
            {},
            {}};
    const glm::dvec3 lo = glm::min(glm::min(tri.a, tri.b), tri.c) - reach;
    const glm::dvec3 hi = glm::max(glm::max(tri.a, tri.b), tri.c) + reach;
    tri.lo = glm::ivec3(glm::ceil(lo));
    tri.hi = glm::ivec3(glm::floor(hi)) + 1;
    all.lo = glm::min(all.lo, tri.lo);
    all.hi = glm::max(all.hi, tri.hi);
    tris.push_back(tri);
  }
  const Box region = intersect(all, Box{glm::ivec3(0), volume.dims()});
  if (tris.empty() || region.empty()) return Box{};
  const int e = volume.brick_edge();
  std::vector<float> dist;
  volume.edit(region, [&](glm::ivec3 origin, std::span<uint8_t> voxels) {
    const Box brick = intersect(Box{origin, origin + glm::ivec3(e)}, region);
    if (brick.empty()) return;
    dist.assign(voxels.size(), std::numeric_limits<float>::infinity());
    bool touched = false;
    for (const Tri& t : tris) {
      const Box box = intersect(brick, Box{t.lo, t.hi});
      if (box.empty()) continue;
      touched = true;
      for (int z = box.lo.z; z < box.hi.z; ++z) {
        for (int y = box.lo.y; y < box.hi.y; ++y) {
          for (int x = box.lo.x; x < box.hi.x; ++x) {
            const glm::ivec3 l = glm::ivec3(x, y, z) - origin;
            float& d = dist[static_cast<size_t>((l.z * e + l.y) * e + l.x)];
            d = std::min(
                d, static_cast<float>(point_triangle_distance(glm::dvec3(x, y, z), t.a, t.b, t.c)));
          }
        }
      }
    }
    if (!touched) return;
    for (size_t i = 0; i < voxels.size(); ++i) {
      if (!std::isfinite(dist[i])) continue;
      const double shell = std::clamp(half - dist[i] + 0.5, 0.0, 1.0);
      const auto value = static_cast<uint8_t>(std::lround(255.0 * shell));
      voxels[i] = mode == ShellMode::kAdd ? std::max(voxels[i], value)
                                          : std::min(voxels[i], static_cast<uint8_t>(255 - value));
    }
  });
  return region;
}

}  // namespace sculpt::core::nurbs
