#include "mesh/stitch_gaps.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace sculpt::core::detail {

void stitch_gaps(glm::vec3 lo, glm::vec3 hi, unsigned coarser_faces,
                 const std::function<int(int face, glm::dvec3 mid)>& coarser_across, Mesh& mesh,
                 MixedLevelStats& st) {
  // Which face planes each vertex lies on: vertices on a face plane have
  // that coordinate exactly (a crossing moves along its edge only).
  std::vector<uint8_t> on_faces(mesh.positions.size(), 0);
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    int faces = 0;
    for (int a = 0; a < 3; ++a) {
      if (mesh.positions[v][a] == lo[a]) faces |= 1 << (2 * a);
      if (mesh.positions[v][a] == hi[a]) faces |= 1 << (2 * a + 1);
    }
    on_faces[v] = static_cast<uint8_t>(faces);
  }
  // Edges in such a face used by one triangle of this brick bound its gaps
  // (an edge in two triangles is inside the surface). Only edges with both
  // ends on one of those planes are counted: a tenth of the mesh's or less.
  auto edge_key = [](uint32_t a, uint32_t c) {
    return (static_cast<uint64_t>(std::min(a, c)) << 32) | std::max(a, c);
  };
  auto in_face = [&](uint32_t a, uint32_t c) {
    return (on_faces[a] & on_faces[c] & coarser_faces) != 0;
  };
  std::vector<uint64_t> face_edges;
  for (const glm::uvec3& t : mesh.triangles)
    for (int c = 0; c < 3; ++c)
      if (in_face(t[c], t[(c + 1) % 3])) face_edges.push_back(edge_key(t[c], t[(c + 1) % 3]));
  if (face_edges.empty()) return;
  std::sort(face_edges.begin(), face_edges.end());
  auto used_once = [&](uint64_t key) {
    const auto [first, last] = std::equal_range(face_edges.begin(), face_edges.end(), key);
    return last - first == 1;
  };
  struct Gap {
    uint64_t group;  // face and coarse square
    uint32_t from, to;
  };
  std::vector<Gap> gaps;
  for (const glm::uvec3& t : mesh.triangles)
    for (int c = 0; c < 3; ++c) {
      const uint32_t from = t[c], to = t[(c + 1) % 3];
      if (!in_face(from, to) || !used_once(edge_key(from, to))) continue;
      // The first face both ends lie on (an edge along a brick's edge lies
      // in two); a same-level face is welded, a finer one is its stitch.
      const int face = std::countr_zero(static_cast<unsigned>(on_faces[from] & on_faces[to]));
      if (((coarser_faces >> face) & 1) == 0) continue;
      const int axis = face / 2;
      // The midpoint in double: in float it would round a vertex one ulp
      // off the plane onto it.
      const glm::dvec3 mid =
          0.5 * (glm::dvec3(mesh.positions[from]) + glm::dvec3(mesh.positions[to]));
      const int lambda = coarser_across(face, mid);
      if (lambda < 0) continue;
      const double big = 1 << lambda;
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const auto su = static_cast<uint64_t>(std::floor(mid[u] / big));
      const auto sv = static_cast<uint64_t>(std::floor(mid[v] / big));
      gaps.push_back({static_cast<uint64_t>(face) | (su << 3) | (sv << 23), from, to});
    }
  std::sort(gaps.begin(), gaps.end(), [](const Gap& a, const Gap& c) {
    return a.group != c.group ? a.group < c.group : a.from < c.from;
  });

  // Fans the loop (a polyline closed by its chord) from its centroid, each
  // triangle walking the loop backwards, so every loop edge ends up in two
  // triangles.
  std::vector<uint32_t> loop;
  auto fill = [&] {
    if (loop.size() < 3) return;  // one segment: the coarse side's own edge
    ++st.stitch_loops;
    glm::vec3 centre(0.0f), normal(0.0f);
    for (uint32_t v : loop) {
      centre += mesh.positions[v];
      normal += mesh.normals[v];
    }
    const auto c = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.push_back(centre / static_cast<float>(loop.size()));
    const float len = glm::length(normal);
    mesh.normals.push_back(len > 0.0f ? normal / len : mesh.normals[loop[0]]);
    for (size_t i = 0; i < loop.size(); ++i) {
      mesh.triangles.emplace_back(c, loop[(i + 1) % loop.size()], loop[i]);
      ++st.stitch_triangles;
    }
  };
  std::vector<uint8_t> done;
  for (size_t g0 = 0; g0 < gaps.size();) {
    size_t g1 = g0;
    while (g1 < gaps.size() && gaps[g1].group == gaps[g0].group)
      ++g1;
    const std::span<const Gap> group(&gaps[g0], g1 - g0);
    done.assign(group.size(), 0);
    auto next_from = [&](uint32_t v) -> int {
      for (size_t i = 0; i < group.size(); ++i)
        if (!done[i] && group[i].from == v) return static_cast<int>(i);
      return -1;
    };
    auto walk = [&](size_t first) {
      loop.clear();
      loop.push_back(group[first].from);
      for (int i = static_cast<int>(first); i >= 0;
           i = next_from(group[static_cast<size_t>(i)].to)) {
        done[static_cast<size_t>(i)] = 1;
        if (group[static_cast<size_t>(i)].to == loop.front()) break;  // a closed loop
        loop.push_back(group[static_cast<size_t>(i)].to);
      }
    };
    // Polylines, from their starts (no gap edge ends there). Each is closed
    // by the coarser brick's segment between its ends: inside one coarse
    // square both sides see the same bilinear interpolant, whose sample
    // arithmetic is exact (dyadic weights times bytes), so the asymptotic
    // decider pairs the crossings the same way on both.
    for (size_t i = 0; i < group.size(); ++i) {
      bool start = true;
      for (const Gap& g : group)
        if (g.to == group[i].from) start = false;
      if (start && !done[i]) {
        walk(i);
        fill();
      }
    }
    // Closed loops: a contour inside one coarse square, which the coarser
    // brick does not see at all.
    for (size_t i = 0; i < group.size(); ++i)
      if (!done[i]) {
        walk(i);
        fill();
      }
    g0 = g1;
  }
}

}  // namespace sculpt::core::detail
