// Tiling tetrahedra (Payne & Toga 1992, the triangulation Jones & Satherley
// use to avoid the marching cubes ambiguity).

#include "sculpt/core/distance/iso_triangulation.h"

namespace sculpt::core {
namespace {

// Cube corner i at offset (i & 1, (i >> 1) & 1, i >> 2).
constexpr glm::ivec3 corner_offset(int i) {
  return {i & 1, (i >> 1) & 1, i >> 2};
}

// The 6 tetrahedra of Kuhn's split: 0 -> 0 + e_a -> 0 + e_a + e_b -> 7 for each
// ordering (a, b, c) of the axes. Corner bits: x = 1, y = 2, z = 4.
constexpr int kTets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7},
                             {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};

glm::vec3 crossing(glm::vec3 pa, float fa, glm::vec3 pb, float fb) {
  const float t = fa / (fa - fb);
  return pa + t * (pb - pa);
}

}  // namespace

DenseGrid<float> level_function(const DenseGrid<uint8_t>& density) {
  DenseGrid<float> phi(density.dims());
  for (size_t i = 0; i < density.size(); ++i)
    phi[i] = kInsideDensity - float(density[i]);
  return phi;
}

DenseGrid<uint8_t> inside_mask(const DenseGrid<float>& phi) {
  DenseGrid<uint8_t> mask(phi.dims());
  for (size_t i = 0; i < phi.size(); ++i)
    mask[i] = phi[i] < 0.0f ? 1 : 0;
  return mask;
}

bool cell_is_transverse(const DenseGrid<float>& phi, glm::ivec3 c) {
  int inside = 0;
  for (int i = 0; i < 8; ++i) {
    const glm::ivec3 p = c + corner_offset(i);
    inside += phi.at(p.x, p.y, p.z) < 0.0f;
  }
  return inside != 0 && inside != 8;
}

int cell_triangles(const DenseGrid<float>& phi, glm::ivec3 c,
                   std::array<Triangle3, kMaxCellTriangles>& out) {
  float f[8];
  glm::vec3 p[8];
  int inside = 0;
  for (int i = 0; i < 8; ++i) {
    const glm::ivec3 q = c + corner_offset(i);
    f[i] = phi.at(q.x, q.y, q.z);
    p[i] = glm::vec3(q);
    inside |= (f[i] < 0.0f) << i;
  }
  if (inside == 0 || inside == 0xff) return 0;
  int n = 0;
  for (const auto& tet : kTets) {
    int in[4], out_[4], ni = 0, no = 0;
    for (int k : tet) {
      if (f[k] < 0.0f)
        in[ni++] = k;
      else
        out_[no++] = k;
    }
    if (ni == 0 || no == 0) continue;
    auto x = [&](int a, int b) { return crossing(p[a], f[a], p[b], f[b]); };
    if (ni == 1) {
      out[n++] = {x(in[0], out_[0]), x(in[0], out_[1]), x(in[0], out_[2])};
    } else if (no == 1) {
      out[n++] = {x(in[0], out_[0]), x(in[1], out_[0]), x(in[2], out_[0])};
    } else {
      // Two in, two out: a quad of four crossings, split in two.
      const glm::vec3 q0 = x(in[0], out_[0]), q1 = x(in[0], out_[1]);
      const glm::vec3 q2 = x(in[1], out_[1]), q3 = x(in[1], out_[0]);
      out[n++] = {q0, q1, q2};
      out[n++] = {q0, q2, q3};
    }
  }
  return n;
}

std::vector<Triangle3> triangulate_iso_surface(const DenseGrid<float>& phi) {
  std::vector<Triangle3> tris;
  const glm::ivec3 d = phi.dims();
  std::array<Triangle3, kMaxCellTriangles> buf;
  for (int z = 0; z + 1 < d.z; ++z)
    for (int y = 0; y + 1 < d.y; ++y)
      for (int x = 0; x + 1 < d.x; ++x) {
        const int n = cell_triangles(phi, {x, y, z}, buf);
        tris.insert(tris.end(), buf.begin(), buf.begin() + n);
      }
  return tris;
}

}  // namespace sculpt::core
