#include "sculpt/core/mesh/mesh.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <tuple>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace sculpt::core {

MeshTopology check_topology(const Mesh& mesh) {
  MeshTopology t;
  t.faces = static_cast<int64_t>(mesh.triangles.size());
  // Directed edges (from, to); an undirected edge appears as its two directions.
  struct Directed {
    uint32_t lo, hi;
    bool forward;
    bool operator<(const Directed& o) const {
      return std::tie(lo, hi, forward) < std::tie(o.lo, o.hi, o.forward);
    }
  };
  std::vector<Directed> edges;
  edges.reserve(mesh.triangles.size() * 3);
  // Link of each vertex: the edge opposite to it in each of its triangles.
  struct Link {
    uint32_t v, a, b;
    bool operator<(const Link& o) const { return std::tie(v, a, b) < std::tie(o.v, o.a, o.b); }
  };
  std::vector<Link> links;
  links.reserve(mesh.triangles.size() * 3);
  for (const glm::uvec3& tri : mesh.triangles) {
    if (tri.x == tri.y || tri.y == tri.z || tri.z == tri.x) {
      ++t.degenerate_triangles;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = tri[k], b = tri[(k + 1) % 3], c = tri[(k + 2) % 3];
      edges.push_back({std::min(a, b), std::max(a, b), a < b});
      links.push_back({a, b, c});
    }
  }
  std::sort(edges.begin(), edges.end());
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    int forward = 0;
    while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) {
      forward += edges[j].forward;
      ++j;
    }
    const size_t uses = j - i;
    ++t.edges;
    if (uses == 1) ++t.boundary_edges;
    if (uses > 2) ++t.nonmanifold_edges;
    if (uses == 2 && forward != 1) ++t.misoriented_edges;
    i = j;
  }
  // A manifold vertex's link edges chain into exactly one cycle.
  std::sort(links.begin(), links.end());
  for (size_t i = 0; i < links.size();) {
    size_t j = i;
    while (j < links.size() && links[j].v == links[i].v)
      ++j;
    ++t.vertices;
    const size_t n = j - i;
    uint32_t at = links[i].a;
    size_t steps = 0;
    while (steps <= n) {
      // links[i..j) are sorted by a: find the link edge leaving `at`.
      auto it =
          std::lower_bound(links.begin() + static_cast<ptrdiff_t>(i),
                           links.begin() + static_cast<ptrdiff_t>(j), Link{links[i].v, at, 0});
      if (it == links.begin() + static_cast<ptrdiff_t>(j) || it->a != at) break;
      at = it->b;
      ++steps;
      if (at == links[i].a) break;
    }
    if (steps != n || at != links[i].a) ++t.nonmanifold_vertices;
    i = j;
  }
  return t;
}

double surface_area(const Mesh& mesh) {
  double area = 0.0;
  for (const glm::uvec3& tri : mesh.triangles) {
    const glm::dvec3 a = mesh.positions[tri.x], b = mesh.positions[tri.y],
                     c = mesh.positions[tri.z];
    area += 0.5 * glm::length(glm::cross(b - a, c - a));
  }
  return area;
}

double enclosed_volume(const Mesh& mesh) {
  double volume = 0.0;
  for (const glm::uvec3& tri : mesh.triangles) {
    const glm::dvec3 a = mesh.positions[tri.x], b = mesh.positions[tri.y],
                     c = mesh.positions[tri.z];
    volume += glm::dot(a, glm::cross(b, c));
  }
  return volume / 6.0;
}

int64_t component_count(const Mesh& mesh) {
  std::vector<uint32_t> parent(mesh.positions.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](uint32_t x) {
    while (parent[x] != x)
      x = parent[x] = parent[parent[x]];
    return x;
  };
  std::vector<uint8_t> used(mesh.positions.size(), 0);
  for (const glm::uvec3& tri : mesh.triangles) {
    for (int k = 0; k < 3; ++k)
      used[tri[k]] = 1;
    parent[find(tri.y)] = find(tri.x);
    parent[find(tri.z)] = find(tri.x);
  }
  int64_t roots = 0;
  for (uint32_t v = 0; v < parent.size(); ++v)
    roots += used[v] && find(v) == v;
  return roots;
}

MeshBounds mesh_bounds(const Mesh& mesh) {
  MeshBounds b{glm::vec3(std::numeric_limits<float>::max()),
               glm::vec3(std::numeric_limits<float>::lowest())};
  for (const glm::vec3& p : mesh.positions) {
    b.lo = glm::min(b.lo, p);
    b.hi = glm::max(b.hi, p);
  }
  return b;
}

}  // namespace sculpt::core
