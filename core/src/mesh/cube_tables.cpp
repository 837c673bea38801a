#include "mesh/cube_tables.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <map>

#include <glm/vec2.hpp>

namespace sculpt::core::detail {
namespace {

bool edges_share_face(const CubeTables& t, int e1, int e2) {
  for (const auto& fe : t.face_edges) {
    const bool has1 = std::find(fe.begin(), fe.end(), e1) != fe.end();
    const bool has2 = std::find(fe.begin(), fe.end(), e2) != fe.end();
    if (has1 && has2) return true;
  }
  return false;
}

int edge_between(int a, int b) {
  for (int e = 0; e < 12; ++e) {
    if ((kEdgeCorners[e][0] == a && kEdgeCorners[e][1] == b) ||
        (kEdgeCorners[e][0] == b && kEdgeCorners[e][1] == a))
      return e;
  }
  assert(false);
  return -1;
}

CubeTables build_tables() {
  CubeTables t;
  for (int f = 0; f < 6; ++f) {
    const int axis = f / 2, side = f % 2;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    // (u, v, +axis) is right-handed: counter-clockwise in (u, v) faces +axis.
    std::array<glm::ivec2, 4> uv = {{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
    if (side == 0) uv = {{{0, 0}, {0, 1}, {1, 1}, {1, 0}}};
    for (int i = 0; i < 4; ++i) {
      glm::ivec3 p(0);
      p[axis] = side;
      p[u] = uv[i].x;
      p[v] = uv[i].y;
      t.face_corners[f][i] = static_cast<uint8_t>(p.x + 2 * p.y + 4 * p.z);
    }
    for (int i = 0; i < 4; ++i) {
      t.face_edges[f][i] =
          static_cast<uint8_t>(edge_between(t.face_corners[f][i], t.face_corners[f][(i + 1) % 4]));
    }
  }
  t.entry_begin.push_back(0);
  t.centre_begin.push_back(0);
  for (int c = 0; c < 256; ++c) {
    auto inside = [c](int corner) { return ((c >> corner) & 1) != 0; };
    std::vector<int> amb_faces;
    for (int f = 0; f < 6; ++f) {
      const auto& fc = t.face_corners[f];
      if (inside(fc[0]) == inside(fc[2]) && inside(fc[1]) == inside(fc[3]) &&
          inside(fc[0]) != inside(fc[1])) {
        t.ambiguous[c] |= static_cast<uint8_t>(1 << f);
        amb_faces.push_back(f);
      }
    }
    t.first_entry[c] = static_cast<uint32_t>(t.entry_begin.size() - 1);
    for (int d = 0; d < (1 << amb_faces.size()); ++d) {
      // next[e]: the edge the surface's boundary reaches after edge e.
      std::array<int, 12> next;
      next.fill(-1);
      for (int f = 0; f < 6; ++f) {
        const auto& fc = t.face_corners[f];
        bool connect = false;
        for (size_t j = 0; j < amb_faces.size(); ++j)
          if (amb_faces[j] == f) connect = ((d >> j) & 1) != 0;
        for (int i = 0; i < 4; ++i) {
          // Walking the face counter-clockwise, a segment runs from an
          // outside-to-inside crossing to an inside-to-outside one, so the
          // loops wind counter-clockwise seen from outside the material.
          if (inside(fc[i]) || !inside(fc[(i + 1) % 4])) continue;
          const int step = connect ? 3 : 1;  // previous or next crossing
          for (int k = 1, j = (i + step) % 4; k < 4; ++k, j = (j + step) % 4) {
            if (inside(fc[j]) && !inside(fc[(j + 1) % 4])) {
              next[t.face_edges[f][i]] = t.face_edges[f][j];
              break;
            }
          }
        }
      }
      std::array<bool, 12> done{};
      for (int e0 = 0; e0 < 12; ++e0) {
        if (next[e0] < 0 || done[e0]) continue;
        std::vector<int> loop;
        for (int e = e0; !done[e]; e = next[e]) {
          done[e] = true;
          loop.push_back(e);
          assert(next[e] >= 0);
        }
        // Fan from an apex none of whose diagonals lies on a cell face: such
        // a diagonal could coincide with one in the cell across that face
        // (only on faces crossed four times), giving an edge in four
        // triangles. Loops with no such apex fan from a vertex at their centre.
        const size_t len = loop.size();
        int apex = -1;
        for (size_t a = 0; a < len && apex < 0; ++a) {
          bool ok = true;
          for (size_t k = 2; k + 1 < len && ok; ++k) {
            ok = !edges_share_face(t, loop[a], loop[(a + k) % len]);
          }
          if (ok) apex = static_cast<int>(a);
        }
        if (apex >= 0) {
          for (size_t k = 1; k + 1 < len; ++k) {
            t.tri_edges.push_back(static_cast<uint8_t>(loop[static_cast<size_t>(apex)]));
            t.tri_edges.push_back(static_cast<uint8_t>(loop[(apex + k) % len]));
            t.tri_edges.push_back(static_cast<uint8_t>(loop[(apex + k + 1) % len]));
          }
        } else {
          const auto centre =
              static_cast<uint8_t>(12 + t.centre_masks.size() - t.centre_begin.back());
          assert(centre < 16);
          uint16_t mask = 0;
          for (int e : loop)
            mask |= static_cast<uint16_t>(1u << e);
          t.centre_masks.push_back(mask);
          for (size_t k = 0; k < len; ++k) {
            t.tri_edges.push_back(centre);
            t.tri_edges.push_back(static_cast<uint8_t>(loop[k]));
            t.tri_edges.push_back(static_cast<uint8_t>(loop[(k + 1) % len]));
          }
        }
      }
      uint16_t edges = 0;
      for (size_t k = t.entry_begin.back(); k < t.tri_edges.size(); ++k) {
        if (t.tri_edges[k] < 12) edges |= static_cast<uint16_t>(1u << t.tri_edges[k]);
      }
      for (size_t k = t.centre_begin.back(); k < t.centre_masks.size(); ++k)
        edges |= t.centre_masks[k];
      t.entry_edges.push_back(edges);
      t.max_triangles = std::max(
          t.max_triangles, static_cast<uint32_t>((t.tri_edges.size() - t.entry_begin.back()) / 3));
      t.max_centres = std::max(
          t.max_centres, static_cast<uint32_t>(t.centre_masks.size() - t.centre_begin.back()));
      t.entry_begin.push_back(static_cast<uint32_t>(t.tri_edges.size()));
      t.centre_begin.push_back(static_cast<uint32_t>(t.centre_masks.size()));
    }
  }
  // The march writes kFixedTriangles triangles of every entry before it
  // counts them; the last entry's may read past its end.
  t.tri_edges.resize(t.tri_edges.size() + 3 * kFixedTriangles, 0);
  return t;
}

}  // namespace

const CubeTables& cube_tables() {
  static const CubeTables t = build_tables();
  return t;
}

}  // namespace sculpt::core::detail
