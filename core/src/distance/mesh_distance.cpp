#include "sculpt/core/distance/mesh_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "sculpt/core/distance/exact_edt.h"
#include "sculpt/core/distance/point_triangle.h"
#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

float corner_angle(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  const glm::vec3 u = b - a, v = c - a;
  const float lu = glm::length(u), lv = glm::length(v);
  if (lu == 0.0f || lv == 0.0f) return 0.0f;
  return std::acos(std::clamp(glm::dot(u, v) / (lu * lv), -1.0f, 1.0f));
}

}  // namespace

MeshDistance::MeshDistance(const Mesh& mesh) : mesh_(mesh) {
  const auto& P = mesh.positions;
  const size_t F = mesh.triangles.size();
  face_normal_.resize(F);
  edge_normal_.assign(3 * F, glm::vec3(0.0f));
  vertex_normal_.assign(P.size(), glm::vec3(0.0f));
  std::unordered_map<uint64_t, glm::vec3> edge_sum;
  edge_sum.reserve(3 * F);
  auto key = [](uint32_t a, uint32_t b) {
    return (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
  };
  for (size_t t = 0; t < F; ++t) {
    const glm::uvec3 f = mesh.triangles[t];
    const glm::vec3 a = P[f.x], b = P[f.y], c = P[f.z];
    const glm::vec3 n = glm::cross(b - a, c - a);
    const float len = glm::length(n);
    face_normal_[t] = len > 0.0f ? n / len : glm::vec3(0.0f);
    vertex_normal_[f.x] += corner_angle(a, b, c) * face_normal_[t];
    vertex_normal_[f.y] += corner_angle(b, c, a) * face_normal_[t];
    vertex_normal_[f.z] += corner_angle(c, a, b) * face_normal_[t];
    edge_sum[key(f.x, f.y)] += face_normal_[t];
    edge_sum[key(f.y, f.z)] += face_normal_[t];
    edge_sum[key(f.z, f.x)] += face_normal_[t];
  }
  for (size_t t = 0; t < F; ++t) {
    const glm::uvec3 f = mesh.triangles[t];
    edge_normal_[3 * t + 0] = edge_sum[key(f.x, f.y)];
    edge_normal_[3 * t + 1] = edge_sum[key(f.y, f.z)];
    edge_normal_[3 * t + 2] = edge_sum[key(f.z, f.x)];
  }
}

float MeshDistance::signed_distance_to(glm::vec3 p, uint32_t t) const {
  const glm::uvec3 f = mesh_.triangles[t];
  const auto& P = mesh_.positions;
  const ClosestPoint c = closest_point_on_triangle(p, P[f.x], P[f.y], P[f.z]);
  glm::vec3 n;
  switch (c.feature) {
    case TriangleFeature::kFace:
      n = face_normal_[t];
      break;
    case TriangleFeature::kVertexA:
      n = vertex_normal_[f.x];
      break;
    case TriangleFeature::kVertexB:
      n = vertex_normal_[f.y];
      break;
    case TriangleFeature::kVertexC:
      n = vertex_normal_[f.z];
      break;
    case TriangleFeature::kEdgeAB:
      n = edge_normal_[3 * t + 0];
      break;
    case TriangleFeature::kEdgeBC:
      n = edge_normal_[3 * t + 1];
      break;
    default:
      n = edge_normal_[3 * t + 2];
      break;
  }
  const float d = std::sqrt(c.distance_squared);
  return glm::dot(p - c.point, n) < 0.0f ? -d : d;
}

float MeshDistance::signed_distance_brute(glm::vec3 p) const {
  float best = kInf;
  uint32_t best_t = 0;
  const auto& P = mesh_.positions;
  for (uint32_t t = 0; t < mesh_.triangles.size(); ++t) {
    const glm::uvec3 f = mesh_.triangles[t];
    const float d = point_triangle_distance_squared(p, P[f.x], P[f.y], P[f.z]);
    if (d < best) {
      best = d;
      best_t = t;
    }
  }
  return mesh_.triangles.empty() ? kInf : signed_distance_to(p, best_t);
}

NarrowBand mesh_narrow_band(const MeshDistance& md, glm::ivec3 dims,
                            const NarrowBandOptions& options) {
  const Mesh& mesh = md.mesh();
  const float band = options.band;
  const float band2 = band * band;
  NarrowBand out{DenseGrid<float>(dims, kInf), DenseGrid<int32_t>(dims, -1)};
  if (voxel_count(dims) == 0) return out;
  // Slabs of z: each thread owns the voxels of its slab, so no two threads
  // write one voxel; a triangle is visited by every slab its band meets.
  constexpr int kSlab = 4;
  const int slabs = (dims.z + kSlab - 1) / kSlab;
  std::vector<std::vector<uint32_t>> bucket(slabs);
  for (uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3 f = mesh.triangles[t];
    const float zlo =
        std::min({mesh.positions[f.x].z, mesh.positions[f.y].z, mesh.positions[f.z].z});
    const float zhi =
        std::max({mesh.positions[f.x].z, mesh.positions[f.y].z, mesh.positions[f.z].z});
    const int s0 = std::max(0, int(std::ceil(zlo - band)) / kSlab);
    const int s1 = std::min(slabs - 1, int(std::floor(zhi + band)) / kSlab);
    for (int s = s0; s <= s1; ++s)
      bucket[s].push_back(t);
  }
  DenseGrid<float>& dist = out.distance;  // squared until the sign pass
  DenseGrid<int32_t>& tri = out.triangle;
  parallel_for(
      slabs,
      [&](int64_t s) {
        const int z0 = int(s) * kSlab, z1 = std::min(dims.z, z0 + kSlab);
        for (uint32_t t : bucket[s]) {
          const glm::uvec3 f = mesh.triangles[t];
          const glm::vec3 a = mesh.positions[f.x], b = mesh.positions[f.y], c = mesh.positions[f.z];
          const glm::vec3 lo = glm::min(a, glm::min(b, c)) - band;
          const glm::vec3 hi = glm::max(a, glm::max(b, c)) + band;
          const glm::ivec3 ilo = glm::max(glm::ivec3(glm::ceil(lo)), glm::ivec3(0, 0, z0));
          const glm::ivec3 ihi =
              glm::min(glm::ivec3(glm::floor(hi)), glm::ivec3(dims.x - 1, dims.y - 1, z1 - 1));
          // Only voxels within band of the triangle's bounding ball can be
          // in its band: per row, the x-range where the row meets that
          // ball; then the plane test rejects with one dot product.
          const glm::vec3 centre = (a + b + c) / 3.0f;
          const float radius = std::sqrt(
              std::max({glm::dot(a - centre, a - centre), glm::dot(b - centre, b - centre),
                        glm::dot(c - centre, c - centre)}));
          const float ball = band + radius;
          const glm::vec3 ab = b - a, ac = c - a;
          const glm::vec3 n = glm::cross(ab, ac);
          const float nlen = glm::length(n);
          const glm::vec3 un = nlen > 0.0f ? n / nlen : glm::vec3(0.0f);
          for (int z = ilo.z; z <= ihi.z; ++z)
            for (int y = ilo.y; y <= ihi.y; ++y) {
              const float dy = float(y) - centre.y, dz = float(z) - centre.z;
              const float rest = ball * ball - dy * dy - dz * dz;
              if (rest < 0.0f) continue;
              const float half = std::sqrt(rest);
              const int x0 = std::max(ilo.x, int(std::ceil(centre.x - half)));
              const int x1 = std::min(ihi.x, int(std::floor(centre.x + half)));
              const size_t row = dist.index(0, y, z);
              for (int x = x0; x <= x1; ++x) {
                const glm::vec3 p{float(x), float(y), float(z)};
                const float h = glm::dot(p - a, un);
                const float cur = std::min(dist[row + x], band2);
                if (h * h >= cur) continue;
                // Ball test: the triangle lies within `radius` of its centre,
                // so it cannot beat the current best when the centre is
                // farther than best + radius. Near a surface most of the
                // neighbouring triangles fail here, not in the plane test.
                const glm::vec3 pc = p - centre;
                const float reach = std::sqrt(cur) + radius;
                if (glm::dot(pc, pc) >= reach * reach) continue;
                const float d2 = triangle_distance2(p, a, ab, ac);
                // Strictly nearer only: ties keep the first triangle in
                // bucket order, the same for any thread count.
                if (d2 < cur) {
                  dist[row + x] = d2;
                  tri[row + x] = int32_t(t);
                }
              }
            }
        }
        // Sign and square root for the slab's voxels.
        for (size_t i = dist.index(0, 0, z0);
             i < dist.index(0, 0, z1 - 1) + size_t(dims.x) * dims.y; ++i) {
          if (tri[i] < 0) continue;
          const int x = int(i % size_t(dims.x)), y = int((i / size_t(dims.x)) % size_t(dims.y));
          const int z = int(i / (size_t(dims.x) * dims.y));
          dist[i] =
              md.signed_distance_to(glm::vec3(float(x), float(y), float(z)), uint32_t(tri[i]));
        }
      },
      options.threads);
  return out;
}

DenseGrid<float> mesh_signed_distance(const MeshDistance& md, glm::ivec3 dims, int threads) {
  NarrowBand nb = mesh_narrow_band(md, dims, NarrowBandOptions{2.0f, threads});
  DenseGrid<uint8_t> seeds(dims, 0);
  for (size_t i = 0; i < seeds.size(); ++i)
    seeds[i] = nb.triangle[i] >= 0;
  const FeatureTransform ft = feature_transform(seeds, 1, threads);
  DenseGrid<float> out = std::move(nb.distance);
  const Mesh& mesh = md.mesh();
  parallel_for(
      dims.z,
      [&](int64_t z) {
        const size_t slice = size_t(dims.x) * dims.y;
        for (size_t i = size_t(z) * slice; i < size_t(z + 1) * slice; ++i) {
          if (nb.triangle[i] >= 0) continue;
          const int32_t s = ft.nearest[i];
          if (s < 0) continue;  // empty band: +infinity stays
          const int x = int(i % size_t(dims.x)), y = int((i / size_t(dims.x)) % size_t(dims.y));
          // The closest triangles of the nearest band voxel and of its
          // neighbours: one triangle alone can miss the nearest one by a few
          // hundredths of a voxel far from a curved surface.
          const glm::vec3 p{float(x), float(y), float(z)};
          const glm::ivec3 sc(s % dims.x, (s / dims.x) % dims.y, s / (dims.x * dims.y));
          int32_t seen[27];
          int n_seen = 0;
          float best = kInf;
          for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx) {
                const glm::ivec3 q = sc + glm::ivec3(dx, dy, dz);
                if (!nb.triangle.in_bounds(q.x, q.y, q.z)) continue;
                const int32_t t = nb.triangle.at(q.x, q.y, q.z);
                if (t < 0 || std::find(seen, seen + n_seen, t) != seen + n_seen) continue;
                seen[n_seen++] = t;
                const glm::uvec3 f = mesh.triangles[size_t(t)];
                best = std::min(
                    best, point_triangle_distance_squared(
                              p, mesh.positions[f.x], mesh.positions[f.y], mesh.positions[f.z]));
              }
          const float d = std::sqrt(best);
          out[i] = out[size_t(s)] < 0.0f ? -d : d;
        }
      },
      threads);
  return out;
}

VoxelizeMapping fit_mesh_to_grid(const Mesh& mesh, int n, float margin) {
  const auto [lo, hi] = mesh_bounds(mesh);
  const glm::vec3 size = hi - lo;
  const float longest = std::max({size.x, size.y, size.z});
  VoxelizeMapping m;
  m.scale = longest > 0.0f ? (float(n - 1) - 2.0f * margin) / longest : 1.0f;
  m.offset = glm::vec3(float(n - 1) * 0.5f) - (lo + hi) * 0.5f * m.scale;
  return m;
}

Mesh transform_mesh(const Mesh& mesh, const VoxelizeMapping& mapping) {
  Mesh out = mesh;
  for (glm::vec3& p : out.positions)
    p = p * mapping.scale + mapping.offset;
  out.normals.clear();
  return out;
}

}  // namespace sculpt::core
