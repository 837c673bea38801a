#include "sculpt/core/mesh/print_check.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

#include <glm/geometric.hpp>

#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

// Does the segment p -> q pass through triangle (a, b, c)? Moller-Trumbore
// with the segment's parameter in [0, 1]; parallel (coplanar) is no.
bool segment_hits_triangle(glm::dvec3 p, glm::dvec3 q, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  constexpr double kEps = 1e-12;
  const glm::dvec3 dir = q - p;
  const glm::dvec3 e1 = b - a;
  const glm::dvec3 e2 = c - a;
  const glm::dvec3 h = glm::cross(dir, e2);
  const double det = glm::dot(e1, h);
  if (std::abs(det) < kEps * glm::length(e1) * glm::length(e2) * glm::length(dir)) return false;
  const double inv = 1.0 / det;
  const glm::dvec3 s = p - a;
  // Strictly inside, by a margin: a segment that only touches the triangle
  // (a vertex on the other's edge after a collapse) is contact, not a
  // crossing, and rounding must not make a shared edge one.
  constexpr double kInside = 1e-7;
  const double u = inv * glm::dot(s, h);
  if (u <= kInside || u >= 1.0 - kInside) return false;
  const glm::dvec3 qv = glm::cross(s, e1);
  const double v = inv * glm::dot(dir, qv);
  if (v <= kInside || u + v >= 1.0 - kInside) return false;
  const double t = inv * glm::dot(e2, qv);
  return t > kInside && t < 1.0 - kInside;
}

bool triangles_intersect(const glm::dvec3 (&x)[3], const glm::dvec3 (&y)[3]) {
  for (int i = 0; i < 3; ++i) {
    if (segment_hits_triangle(x[i], x[(i + 1) % 3], y[0], y[1], y[2])) return true;
    if (segment_hits_triangle(y[i], y[(i + 1) % 3], x[0], x[1], x[2])) return true;
  }
  return false;
}

bool share_vertex(const glm::uvec3& a, const glm::uvec3& b) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (a[i] == b[j]) return true;
  return false;
}

}  // namespace

int64_t count_self_intersections(const Mesh& mesh, int64_t limit) {
  return static_cast<int64_t>(self_intersecting_pairs(mesh, limit).size());
}

std::vector<std::pair<uint32_t, uint32_t>> self_intersecting_pairs(const Mesh& mesh,
                                                                   int64_t limit) {
  std::vector<std::pair<uint32_t, uint32_t>> found;
  const size_t n = mesh.triangles.size();
  if (n < 2 || limit <= 0) return found;
  // Cells about twice the mean edge: a triangle spans a few cells at most.
  double edge_sum = 0.0;
  for (const glm::uvec3& t : mesh.triangles)
    edge_sum += glm::length(mesh.positions[t[1]] - mesh.positions[t[0]]);
  const double cell = std::max(2.0 * edge_sum / static_cast<double>(n), 1e-6);
  const MeshBounds bounds = mesh_bounds(mesh);
  const glm::dvec3 origin(bounds.lo);
  auto cell_of = [&](glm::dvec3 p) { return glm::ivec3(glm::floor((p - origin) / cell)); };
  auto key = [](glm::ivec3 c) {
    return (static_cast<uint64_t>(static_cast<uint32_t>(c.x)) * 73856093u) ^
           (static_cast<uint64_t>(static_cast<uint32_t>(c.y)) * 19349663u) ^
           (static_cast<uint64_t>(static_cast<uint32_t>(c.z)) * 83492791u);
  };
  struct Entry {
    glm::ivec3 cell;
    uint32_t triangle;
  };
  std::unordered_map<uint64_t, std::vector<Entry>> grid;
  grid.reserve(n * 2);
  std::vector<std::pair<glm::ivec3, glm::ivec3>> spans(n);
  for (size_t i = 0; i < n; ++i) {
    const glm::uvec3& t = mesh.triangles[i];
    const glm::dvec3 a(mesh.positions[t[0]]), b(mesh.positions[t[1]]), c(mesh.positions[t[2]]);
    const glm::ivec3 lo = cell_of(glm::min(a, glm::min(b, c)));
    const glm::ivec3 hi = cell_of(glm::max(a, glm::max(b, c)));
    spans[i] = {lo, hi};
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x)
          grid[key({x, y, z})].push_back({{x, y, z}, static_cast<uint32_t>(i)});
  }
  // Tasks of triangles in order, each finding at most `most` of its own:
  // the grid is read-only, and joined in order the first `most` pairs are
  // the same on any number of threads.
  const auto most = static_cast<size_t>(limit);
  constexpr size_t kTrianglesPerTask = 4096;
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> per_task((n + kTrianglesPerTask - 1) /
                                                                   kTrianglesPerTask);
  parallel_for(static_cast<int64_t>(per_task.size()), [&](int64_t task) {
    auto& mine = per_task[static_cast<size_t>(task)];
    const size_t begin = static_cast<size_t>(task) * kTrianglesPerTask;
    const size_t end = std::min(n, begin + kTrianglesPerTask);
    std::vector<uint32_t> candidates;
    for (size_t i = begin; i < end && mine.size() < most; ++i) {
      const glm::uvec3& t = mesh.triangles[i];
      const auto [lo, hi] = spans[i];
      candidates.clear();
      for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y)
          for (int x = lo.x; x <= hi.x; ++x) {
            const auto it = grid.find(key({x, y, z}));
            if (it == grid.end()) continue;
            for (const Entry& e : it->second)
              if (e.triangle > i && e.cell == glm::ivec3(x, y, z)) candidates.push_back(e.triangle);
          }
      std::sort(candidates.begin(), candidates.end());
      candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
      const glm::dvec3 x[3] = {glm::dvec3(mesh.positions[t[0]]), glm::dvec3(mesh.positions[t[1]]),
                               glm::dvec3(mesh.positions[t[2]])};
      for (const uint32_t j : candidates) {
        const glm::uvec3& u = mesh.triangles[j];
        if (share_vertex(t, u)) continue;
        const glm::dvec3 y[3] = {glm::dvec3(mesh.positions[u[0]]), glm::dvec3(mesh.positions[u[1]]),
                                 glm::dvec3(mesh.positions[u[2]])};
        if (!triangles_intersect(x, y)) continue;
        mine.emplace_back(static_cast<uint32_t>(i), j);
        if (mine.size() >= most) break;
      }
    }
  });
  for (const auto& mine : per_task) {
    found.insert(
        found.end(), mine.begin(),
        mine.begin() + static_cast<std::ptrdiff_t>(std::min(mine.size(), most - found.size())));
    if (found.size() >= most) break;
  }
  return found;
}

PrintCheck check_print(const Mesh& mesh, double voxel_mm) {
  PrintCheck c;
  c.topology = check_topology(mesh);
  c.components = component_count(mesh);
  c.self_intersections = count_self_intersections(mesh);
  c.volume_mm3 = enclosed_volume(mesh) * voxel_mm * voxel_mm * voxel_mm;
  const MeshBounds b = mesh_bounds(mesh);
  c.bounds_mm = {b.lo * static_cast<float>(voxel_mm), b.hi * static_cast<float>(voxel_mm)};
  return c;
}

}  // namespace sculpt::core
