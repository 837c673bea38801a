#include "sculpt/core/mesh/mesh.h"

#include <algorithm>
#include <cassert>
#include <limits>
#include <numeric>
#include <span>
#include <tuple>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "mesh/by_vertex.h"

namespace sculpt::core {

using detail::ByVertex;

namespace {

// An undirected edge as its lower end keeps it.
struct Edge {
  uint32_t hi;
  bool forward;  // walked from the lower end to `hi`
  bool operator<(const Edge& o) const { return std::tie(hi, forward) < std::tie(o.hi, o.forward); }
};

bool degenerate(const glm::uvec3& tri) {
  return tri.x == tri.y || tri.y == tri.z || tri.z == tri.x;
}

// The edges of every triangle that is not degenerate, by their lower end.
ByVertex<Edge> edges_by_lower_end(const Mesh& mesh) {
  return ByVertex<Edge>(mesh.positions.size(), [&](auto put) {
    for (const glm::uvec3& tri : mesh.triangles) {
      if (degenerate(tri)) continue;
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = tri[k], b = tri[(k + 1) % 3];
        put(std::min(a, b), Edge{std::max(a, b), a < b});
      }
    }
  });
}

// Calls f(hi, uses, forward_uses) for each undirected edge of the group of
// lower end edges `from` (sorted).
template <class F>
void for_each_edge(std::span<const Edge> from, F f) {
  for (size_t i = 0; i < from.size();) {
    size_t j = i;
    int forward = 0;
    for (; j < from.size() && from[j].hi == from[i].hi; ++j)
      forward += from[j].forward;
    f(from[i].hi, j - i, forward);
    i = j;
  }
}

}  // namespace

MeshTopology check_topology(const Mesh& mesh, std::vector<bool>* border) {
  MeshTopology t;
  if (border != nullptr) border->assign(mesh.positions.size(), false);
  t.faces = static_cast<int64_t>(mesh.triangles.size());
  t.degenerate_triangles = std::ranges::count_if(mesh.triangles, degenerate);
  const ByVertex<Edge> edges = edges_by_lower_end(mesh);
  // Each vertex's link: the edge opposite to it in each of its triangles.
  struct LinkEdge {
    uint32_t a, b;
    bool operator<(const LinkEdge& o) const { return std::tie(a, b) < std::tie(o.a, o.b); }
  };
  const ByVertex<LinkEdge> links(mesh.positions.size(), [&](auto put) {
    for (const glm::uvec3& tri : mesh.triangles) {
      if (degenerate(tri)) continue;
      for (int k = 0; k < 3; ++k)
        put(tri[k], LinkEdge{tri[(k + 1) % 3], tri[(k + 2) % 3]});
    }
  });

  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    // Each edge is used once (a border), twice (walked once each way, else
    // misoriented) or more (non-manifold).
    for_each_edge(edges.of(v), [&](uint32_t hi, size_t uses, int forward) {
      ++t.edges;
      if (uses == 1) {
        ++t.boundary_edges;
        if (border != nullptr) (*border)[v] = (*border)[hi] = true;
      }
      if (uses > 2) ++t.nonmanifold_edges;
      if (uses == 2 && forward != 1) ++t.misoriented_edges;
    });
    // A manifold vertex's link edges chain into exactly one cycle.
    const std::span<const LinkEdge> link = links.of(v);
    if (link.empty()) continue;
    ++t.vertices;
    uint32_t at = link.front().a;
    size_t steps = 0;
    while (steps <= link.size()) {
      // Sorted by a: the link edge leaving `at`.
      const auto it = std::ranges::lower_bound(link, at, {}, &LinkEdge::a);
      if (it == link.end() || it->a != at) break;
      at = it->b;
      ++steps;
      if (at == link.front().a) break;
    }
    if (steps != link.size() || at != link.front().a) ++t.nonmanifold_vertices;
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
