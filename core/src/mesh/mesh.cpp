#include "sculpt/core/mesh/mesh.h"

#include <algorithm>
#include <cassert>
#include <limits>
#include <numeric>
#include <tuple>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace sculpt::core {

MeshTopology check_topology(const Mesh& mesh) {
  MeshTopology t;
  t.faces = static_cast<int64_t>(mesh.triangles.size());
  // Each vertex's entries are grouped by a counting sort over the vertex
  // indices (dense: below positions.size()), so the work is linear in the
  // triangles; sorting all the mesh's edges as tuples took the window's
  // simplifier half its time. A vertex holds the edges it is the lower end
  // of (with their direction) and its link: the edge opposite to it in
  // each of its triangles.
  struct Edge {
    uint32_t hi;
    bool forward;  // walked from the lower end to `hi`
  };
  struct LinkEdge {
    uint32_t a, b;
  };
  const size_t vertex_count = mesh.positions.size();
  std::vector<uint32_t> edge_start(vertex_count + 1, 0), link_start(vertex_count + 1, 0);
  for (const glm::uvec3& tri : mesh.triangles) {
    if (tri.x == tri.y || tri.y == tri.z || tri.z == tri.x) {
      ++t.degenerate_triangles;
      continue;
    }
    assert(std::max({tri.x, tri.y, tri.z}) < vertex_count);
    for (int k = 0; k < 3; ++k) {
      ++edge_start[std::min(tri[k], tri[(k + 1) % 3]) + 1];
      ++link_start[tri[k] + 1];
    }
  }
  std::partial_sum(edge_start.begin(), edge_start.end(), edge_start.begin());
  std::partial_sum(link_start.begin(), link_start.end(), link_start.begin());
  std::vector<Edge> edges(edge_start.back());
  std::vector<LinkEdge> links(link_start.back());
  std::vector<uint32_t> edge_end(edge_start.begin(), edge_start.end() - 1);
  std::vector<uint32_t> link_end(link_start.begin(), link_start.end() - 1);
  for (const glm::uvec3& tri : mesh.triangles) {
    if (tri.x == tri.y || tri.y == tri.z || tri.z == tri.x) continue;
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = tri[k], b = tri[(k + 1) % 3], c = tri[(k + 2) % 3];
      edges[edge_end[std::min(a, b)]++] = {std::max(a, b), a < b};
      links[link_end[a]++] = {b, c};
    }
  }

  for (size_t v = 0; v < vertex_count; ++v) {
    // The undirected edges from v: each used once (a border), twice (walked
    // once each way, else misoriented) or more (non-manifold).
    const auto e0 = edges.begin() + edge_start[v], e1 = edges.begin() + edge_start[v + 1];
    std::sort(e0, e1, [](const Edge& p, const Edge& q) { return p.hi < q.hi; });
    for (auto i = e0; i != e1;) {
      auto j = i;
      int forward = 0;
      for (; j != e1 && j->hi == i->hi; ++j)
        forward += j->forward;
      const auto uses = j - i;
      ++t.edges;
      if (uses == 1) ++t.boundary_edges;
      if (uses > 2) ++t.nonmanifold_edges;
      if (uses == 2 && forward != 1) ++t.misoriented_edges;
      i = j;
    }
    // A manifold vertex's link edges chain into exactly one cycle.
    const auto l0 = links.begin() + link_start[v], l1 = links.begin() + link_start[v + 1];
    if (l0 == l1) continue;
    ++t.vertices;
    std::sort(l0, l1, [](const LinkEdge& p, const LinkEdge& q) {
      return std::tie(p.a, p.b) < std::tie(q.a, q.b);
    });
    const auto n = l1 - l0;
    uint32_t at = l0->a;
    ptrdiff_t steps = 0;
    while (steps <= n) {
      // Sorted by a: the link edge leaving `at`.
      const auto it =
          std::lower_bound(l0, l1, at, [](const LinkEdge& e, uint32_t from) { return e.a < from; });
      if (it == l1 || it->a != at) break;
      at = it->b;
      ++steps;
      if (at == l0->a) break;
    }
    if (steps != n || at != l0->a) ++t.nonmanifold_vertices;
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
