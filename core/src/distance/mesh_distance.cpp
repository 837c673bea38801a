#include "sculpt/core/distance/mesh_distance.h"
#include "sculpt/core/grid/grid_index.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "chunked_groups.h"
#include "sculpt/core/distance/exact_edt.h"
#include "sculpt/core/distance/narrow_band.h"
#include "sculpt/core/mesh/point_triangle.h"
#include "sculpt/core/util/parallel_for.h"
#include "sculpt/core/util/progress.h"

namespace sculpt::core {

using detail::for_chunks;
using detail::group_by;
using detail::Groups;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

float corner_angle(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  const glm::vec3 u = b - a, v = c - a;
  const float lu = glm::length(u), lv = glm::length(v);
  if (lu == 0.0f || lv == 0.0f) return 0.0f;
  return std::acos(std::clamp(glm::dot(u, v) / (lu * lv), -1.0f, 1.0f));
}

}  // namespace

// The sums run per vertex (and per edge, grouped by its lower vertex) over
// the corners in triangle order, as one pass over the triangles would add
// them, so the normals do not depend on the number of threads.
MeshDistance::MeshDistance(const Mesh& mesh) : mesh_(mesh) {
  const auto& P = mesh.positions;
  const auto& T = mesh.triangles;
  const size_t F = T.size();
  face_normal_.resize(F);
  edge_normal_.resize(3 * F);
  vertex_normal_.resize(P.size());
  // Corner k of triangle t is corner 3t + k: vertex T[t][k], edge from
  // T[t][k] to T[t][(k + 1) % 3].
  std::vector<float> angle(3 * F);
  for_chunks(int64_t(F), [&](int64_t t) {
    const glm::uvec3 f = T[size_t(t)];
    const glm::vec3 a = P[f.x], b = P[f.y], c = P[f.z];
    const glm::vec3 n = glm::cross(b - a, c - a);
    const float len = glm::length(n);
    face_normal_[size_t(t)] = len > 0.0f ? n / len : glm::vec3(0.0f);
    angle[3 * size_t(t) + 0] = corner_angle(a, b, c);
    angle[3 * size_t(t) + 1] = corner_angle(b, c, a);
    angle[3 * size_t(t) + 2] = corner_angle(c, a, b);
  });
  const auto corner_vertex = [&](size_t i) { return T[i / 3][int(i % 3)]; };
  const auto edge_end = [&](size_t i) { return T[i / 3][int((i + 1) % 3)]; };
  const Groups at_vertex = group_by(P.size(), 3 * F, corner_vertex);
  for_chunks(int64_t(P.size()), [&](int64_t v) {
    glm::vec3 sum(0.0f);
    for (uint32_t k = at_vertex.start[size_t(v)]; k < at_vertex.start[size_t(v) + 1]; ++k) {
      const uint32_t i = at_vertex.items[k];
      sum += angle[i] * face_normal_[i / 3];
    }
    vertex_normal_[size_t(v)] = sum;
  });
  const Groups at_lower =
      group_by(P.size(), 3 * F, [&](size_t i) { return std::min(corner_vertex(i), edge_end(i)); });
  for_chunks(int64_t(P.size()), [&](int64_t v) {
    const uint32_t* first = at_lower.items.data() + at_lower.start[size_t(v)];
    const uint32_t* last = at_lower.items.data() + at_lower.start[size_t(v) + 1];
    for (const uint32_t* e = first; e != last; ++e) {
      const uint32_t upper = std::max(corner_vertex(*e), edge_end(*e));
      if (std::find_if(first, e, [&](uint32_t o) {
            return std::max(corner_vertex(o), edge_end(o)) == upper;
          }) != e)
        continue;  // this edge's sum is done
      glm::vec3 sum(0.0f);
      for (const uint32_t* o = e; o != last; ++o)
        if (std::max(corner_vertex(*o), edge_end(*o)) == upper) sum += face_normal_[*o / 3];
      for (const uint32_t* o = e; o != last; ++o)
        if (std::max(corner_vertex(*o), edge_end(*o)) == upper) edge_normal_[*o] = sum;
    }
  });
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

DenseGrid<float> mesh_signed_distance(const MeshDistance& md, glm::ivec3 dims, int threads,
                                      Progress* progress) {
  // Units: the band and the feature transform count as one pass over the
  // slices each, then the fill steps per slice.
  ProgressStage stage(progress, 0.0, 1.0, int64_t(dims.z) * 3);
  if (!stage.step(0)) return DenseGrid<float>(dims, kInf);
  const NarrowBand band = mesh_narrow_band(md, dims, NarrowBandOptions{2.0f, threads});
  if (!stage.step(dims.z)) return DenseGrid<float>(dims, kInf);
  const DenseGrid<int32_t> triangle = band.dense_triangle(threads);
  DenseGrid<uint8_t> seeds(dims, 0);
  for (size_t i = 0; i < seeds.size(); ++i)
    seeds[i] = triangle[i] >= 0;
  const FeatureTransform ft = feature_transform(seeds, 1, threads);
  if (!stage.step(dims.z)) return DenseGrid<float>(dims, kInf);
  DenseGrid<float> out = band.dense_distance(threads);
  const Mesh& mesh = md.mesh();
  parallel_for(
      dims.z,
      [&](int64_t z) {
        const size_t slice = size_t(dims.x) * dims.y;
        for (size_t i = size_t(z) * slice; i < size_t(z + 1) * slice; ++i) {
          if (triangle[i] >= 0) continue;
          const int32_t s = ft.nearest[i];
          if (s < 0) continue;  // empty band: +infinity stays
          const int x = int(i % size_t(dims.x)), y = int((i / size_t(dims.x)) % size_t(dims.y));
          // The closest triangles of the nearest band voxel and of its
          // neighbours: one triangle alone can miss the nearest one by a few
          // hundredths of a voxel far from a curved surface.
          const glm::vec3 p{float(x), float(y), float(z)};
          const glm::ivec3 sc = grid_position(s, dims);
          int32_t seen[27];
          int n_seen = 0;
          float best = kInf;
          for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx) {
                const glm::ivec3 q = sc + glm::ivec3(dx, dy, dz);
                if (!triangle.in_bounds(q.x, q.y, q.z)) continue;
                const int32_t t = triangle.at(q.x, q.y, q.z);
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
      threads, stage);
  return out;
}

Result<VoxelizeMapping> fit_mesh_to_grid(const Mesh& mesh, int n, float margin) {
  const auto [lo, hi] = mesh_bounds(mesh);
  const glm::vec3 size = hi - lo;
  const float longest = std::max({size.x, size.y, size.z});
  // A mesh of extent 1e-38 maps by a scale of infinity; one at 1e38 has a
  // centre that overflows. Either way the grid would hold no surface.
  if (!(longest >= kMinMeshExtent) || !std::isfinite(longest)) {
    char text[96];
    std::snprintf(text, sizeof text, "its extent %.3g is outside [%.3g, %.3g]", double(longest),
                  double(kMinMeshExtent), double(std::numeric_limits<float>::max()));
    return Error(text);
  }
  VoxelizeMapping m;
  m.scale = (float(n - 1) - 2.0f * margin) / longest;
  m.offset = glm::vec3(float(n - 1) * 0.5f) - (lo * 0.5f + hi * 0.5f) * m.scale;
  if (!std::isfinite(m.scale) || !std::isfinite(m.offset.x) || !std::isfinite(m.offset.y) ||
      !std::isfinite(m.offset.z)) {
    return Error("its position cannot be mapped to the grid in float precision");
  }
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
