#include "sculpt/core/distance/polygon_distance.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <glm/geometric.hpp>

namespace sculpt::core {
namespace {

constexpr float kFar = std::numeric_limits<float>::infinity();

// Edge from a to b (a polygon's previous vertex to its next, as the even-odd
// rule below reads them).
struct Edge {
  glm::vec2 a, b;
};

float edge_distance2(glm::vec2 p, const Edge& e) {
  const glm::vec2 ab = e.b - e.a;
  const float len2 = glm::dot(ab, ab);
  const float t = len2 > 0.0f ? std::clamp(glm::dot(p - e.a, ab) / len2, 0.0f, 1.0f) : 0.0f;
  const glm::vec2 d = p - (e.a + t * ab);
  return glm::dot(d, d);
}

// Inside by the even-odd rule along +x from each pixel centre: an edge
// crosses row y when exactly one end is above y; the pixel is inside when
// an odd number of crossings lie to its right.
std::vector<uint8_t> inside_mask(glm::ivec2 dims, const std::vector<Edge>& edges,
                                 PolygonDistanceCost& cost) {
  std::vector<std::vector<float>> crossings(static_cast<size_t>(dims.y));
  for (const Edge& e : edges) {
    const float lo = std::min(e.a.y, e.b.y), hi = std::max(e.a.y, e.b.y);
    // Rows lo <= y < hi (vertices lie inside the grid: contours.cpp checks).
    const int first = std::max(0, static_cast<int>(std::ceil(lo)));
    const int last = std::min(dims.y - 1, static_cast<int>(std::ceil(hi)) - 1);
    for (int y = first; y <= last; ++y) {
      const float fy = static_cast<float>(y);
      if ((e.b.y > fy) == (e.a.y > fy)) continue;  // the float test is the rule
      crossings[static_cast<size_t>(y)].push_back((e.a.x - e.b.x) * (fy - e.b.y) / (e.a.y - e.b.y) +
                                                  e.b.x);
    }
  }
  std::vector<uint8_t> inside(static_cast<size_t>(dims.x) * static_cast<size_t>(dims.y), 0);
  for (int y = 0; y < dims.y; ++y) {
    std::vector<float>& row = crossings[static_cast<size_t>(y)];
    cost.crossings += static_cast<int64_t>(row.size());
    std::sort(row.begin(), row.end());
    size_t not_right = 0;  // crossings at or left of x
    for (int x = 0; x < dims.x; ++x) {
      while (not_right < row.size() && row[not_right] <= static_cast<float>(x))
        ++not_right;
      inside[static_cast<size_t>(y) * static_cast<size_t>(dims.x) + static_cast<size_t>(x)] =
          static_cast<uint8_t>((row.size() - not_right) & 1u);
    }
  }
  return inside;
}

// Squared distance and edge of the nearest edge for every pixel within the
// exact band of some edge: each edge visits the pixels around points at most
// half a pixel apart along it, so the cost is its length, not the grid.
void exact_band(glm::ivec2 dims, const std::vector<Edge>& edges, std::vector<float>& best2,
                std::vector<int32_t>& nearest, PolygonDistanceCost& cost) {
  const int reach = static_cast<int>(std::ceil(kExactBand + 0.5f));
  for (size_t k = 0; k < edges.size(); ++k) {
    const Edge& e = edges[k];
    const float length = glm::length(e.b - e.a);
    const int steps = static_cast<int>(std::ceil(length * 2.0f)) + 1;
    for (int s = 0; s <= steps; ++s) {
      const glm::vec2 q = e.a + (e.b - e.a) * (static_cast<float>(s) / static_cast<float>(steps));
      const int cx = static_cast<int>(std::lround(q.x)), cy = static_cast<int>(std::lround(q.y));
      for (int y = std::max(0, cy - reach); y <= std::min(dims.y - 1, cy + reach); ++y)
        for (int x = std::max(0, cx - reach); x <= std::min(dims.x - 1, cx + reach); ++x) {
          const size_t i =
              static_cast<size_t>(y) * static_cast<size_t>(dims.x) + static_cast<size_t>(x);
          const float d2 = edge_distance2({static_cast<float>(x), static_cast<float>(y)}, e);
          ++cost.edge_distances;
          if (d2 < best2[i]) {
            best2[i] = d2;
            nearest[i] = static_cast<int32_t>(k);
          }
        }
    }
  }
}

// For every pixel, the index of its nearest seed pixel (Euclidean, exact),
// in linear time: nearest seed column along each row, then the lower
// envelope of the parabolas (x - column(y'))^2 + (y - y')^2 down each column.
std::vector<int64_t> nearest_seed(glm::ivec2 dims, const std::vector<uint8_t>& seed) {
  const size_t w = static_cast<size_t>(dims.x), h = static_cast<size_t>(dims.y);
  std::vector<int32_t> column(w * h, -1);  // nearest seed's x in the same row
  for (size_t y = 0; y < h; ++y) {
    int32_t last = -1;
    for (size_t x = 0; x < w; ++x) {
      if (seed[y * w + x]) last = static_cast<int32_t>(x);
      column[y * w + x] = last;
    }
    last = -1;
    for (size_t x = w; x-- > 0;) {
      if (seed[y * w + x]) last = static_cast<int32_t>(x);
      const int32_t left = column[y * w + x];
      if (last >= 0 &&
          (left < 0 || last - static_cast<int32_t>(x) < static_cast<int32_t>(x) - left))
        column[y * w + x] = last;
    }
  }
  std::vector<int64_t> out(w * h, -1);
  std::vector<int32_t> v(h);     // rows of the parabolas in the envelope
  std::vector<double> z(h + 1);  // where each one starts
  for (size_t x = 0; x < w; ++x) {
    auto f = [&](size_t y) {
      const int32_t c = column[y * w + x];
      const double dx = static_cast<double>(c) - static_cast<double>(x);
      return dx * dx;
    };
    int k = -1;
    for (size_t q = 0; q < h; ++q) {
      if (column[q * w + x] < 0) continue;
      const double fq = f(q) + static_cast<double>(q) * static_cast<double>(q);
      double s = -std::numeric_limits<double>::infinity();
      while (k >= 0) {
        const size_t p = static_cast<size_t>(v[static_cast<size_t>(k)]);
        s = (fq - (f(p) + static_cast<double>(p) * static_cast<double>(p))) /
            (2.0 * (static_cast<double>(q) - static_cast<double>(p)));
        if (s > z[static_cast<size_t>(k)]) break;
        --k;
      }
      ++k;
      v[static_cast<size_t>(k)] = static_cast<int32_t>(q);
      z[static_cast<size_t>(k)] = k == 0 ? -std::numeric_limits<double>::infinity() : s;
      z[static_cast<size_t>(k) + 1] = std::numeric_limits<double>::infinity();
    }
    if (k < 0) continue;  // no seed in any row: impossible with one edge in the grid
    int j = 0;
    for (size_t y = 0; y < h; ++y) {
      while (z[static_cast<size_t>(j) + 1] < static_cast<double>(y))
        ++j;
      const size_t row = static_cast<size_t>(v[static_cast<size_t>(j)]);
      out[y * w + x] = static_cast<int64_t>(row * w) + column[row * w + x];
    }
  }
  return out;
}

}  // namespace

std::vector<float> polygon_signed_distance(
    glm::ivec2 dims, const std::vector<const std::vector<glm::vec2>*>& polygons,
    PolygonDistanceCost* cost_out) {
  PolygonDistanceCost cost;
  std::vector<Edge> edges;
  for (const std::vector<glm::vec2>* polygon : polygons) {
    const std::vector<glm::vec2>& v = *polygon;
    for (size_t i = 0, j = v.size() - 1; i < v.size(); j = i++)
      edges.push_back(Edge{v[j], v[i]});
  }
  const size_t n = static_cast<size_t>(dims.x) * static_cast<size_t>(dims.y);
  const std::vector<uint8_t> inside = inside_mask(dims, edges, cost);
  std::vector<float> best2(n, kFar);
  std::vector<int32_t> nearest(n, -1);
  exact_band(dims, edges, best2, nearest, cost);
  std::vector<uint8_t> exact(n);
  for (size_t i = 0; i < n; ++i)
    exact[i] = best2[i] <= kExactBand * kExactBand;
  const std::vector<int64_t> seed = nearest_seed(dims, exact);
  std::vector<float> field(n);
  for (size_t i = 0; i < n; ++i) {
    float d2 = best2[i];
    if (!exact[i] && seed[i] >= 0) {
      const glm::vec2 p{static_cast<float>(i % static_cast<size_t>(dims.x)),
                        static_cast<float>(i / static_cast<size_t>(dims.x))};
      d2 = std::min(
          d2, edge_distance2(p, edges[static_cast<size_t>(nearest[static_cast<size_t>(seed[i])])]));
      ++cost.edge_distances;
    }
    const float d = std::sqrt(d2);
    field[i] = inside[i] ? -d : d;
  }
  if (cost_out != nullptr) *cost_out = cost;
  return field;
}

}  // namespace sculpt::core
