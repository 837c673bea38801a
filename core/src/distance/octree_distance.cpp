// An octree over primitive bounding boxes, split at the centre of each node's
// box (a point region octree; nodes are created only for occupied octants,
// the "branch on need" of Wilhelms & Van Gelder that Jones & Satherley use
// for volumes whose size is not a power of two).

#include "sculpt/core/distance/octree_distance.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "sculpt/core/mesh/point_triangle.h"
#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

constexpr int kLeafSize = 8;
constexpr int kMaxDepth = 24;

struct Node {
  glm::vec3 lo, hi;      // bounds of the primitives below
  int32_t first = 0;     // leaf: first primitive in order_; inner: first child
  int32_t count = 0;     // leaf: primitive count; inner: 0
  int32_t children = 0;  // inner: number of children (consecutive)
};

template <class Prim>
class Octree {
 public:
  Octree(const std::vector<Prim>& prims) : prims_(prims) {
    order_.resize(prims.size());
    for (size_t i = 0; i < prims.size(); ++i)
      order_[i] = int32_t(i);
    if (prims.empty()) return;
    nodes_.push_back(Node{});
    build(0, 0, int32_t(prims.size()), 0);
  }

  // Nearest primitive to p given a first guess `hint` (-1: none).
  std::pair<float, int32_t> nearest(glm::vec3 p, int32_t hint) const {
    float best = std::numeric_limits<float>::infinity();
    int32_t best_id = -1;
    if (nodes_.empty()) return {best, best_id};
    if (hint >= 0) {
      best = dist2(p, prims_[hint]);
      best_id = hint;
    }
    int32_t stack[8 * kMaxDepth + 8];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = nodes_[stack[--top]];
      if (point_box_distance_squared(p, n.lo, n.hi) >= best) continue;
      if (n.count > 0) {
        for (int32_t k = n.first; k < n.first + n.count; ++k) {
          const float d = dist2(p, prims_[order_[k]]);
          if (d < best || (d == best && order_[k] < best_id)) {
            best = d;
            best_id = order_[k];
          }
        }
        continue;
      }
      // Children nearest first: push them farthest first.
      std::pair<float, int32_t> kids[8];
      int m = 0;
      for (int32_t c = n.first; c < n.first + n.children; ++c) {
        const float d = point_box_distance_squared(p, nodes_[c].lo, nodes_[c].hi);
        if (d < best) kids[m++] = {d, c};
      }
      for (int i = 1; i < m; ++i)  // insertion sort, farthest first
        for (int j = i; j > 0 && kids[j - 1].first < kids[j].first; --j)
          std::swap(kids[j - 1], kids[j]);
      for (int i = 0; i < m; ++i)
        stack[top++] = kids[i].second;
    }
    return {best, best_id};
  }

 private:
  static float dist2(glm::vec3 p, const glm::vec3& q) {
    const glm::vec3 d = p - q;
    return glm::dot(d, d);
  }
  static float dist2(glm::vec3 p, const Triangle3& t) {
    return point_triangle_distance_squared(p, t.a, t.b, t.c);
  }
  static glm::vec3 lo_of(const glm::vec3& q) { return q; }
  static glm::vec3 hi_of(const glm::vec3& q) { return q; }
  static glm::vec3 lo_of(const Triangle3& t) { return glm::min(t.a, glm::min(t.b, t.c)); }
  static glm::vec3 hi_of(const Triangle3& t) { return glm::max(t.a, glm::max(t.b, t.c)); }

  void build(int32_t node, int32_t first, int32_t count, int depth) {
    glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-lo);
    for (int32_t k = first; k < first + count; ++k) {
      lo = glm::min(lo, lo_of(prims_[order_[k]]));
      hi = glm::max(hi, hi_of(prims_[order_[k]]));
    }
    nodes_[node].lo = lo;
    nodes_[node].hi = hi;
    if (count <= kLeafSize || depth >= kMaxDepth) {
      nodes_[node].first = first;
      nodes_[node].count = count;
      return;
    }
    const glm::vec3 mid = (lo + hi) * 0.5f;
    auto octant = [&](int32_t id) {
      const glm::vec3 c = (lo_of(prims_[id]) + hi_of(prims_[id])) * 0.5f;
      return int(c.x > mid.x) | int(c.y > mid.y) << 1 | int(c.z > mid.z) << 2;
    };
    int32_t counts[8] = {};
    for (int32_t k = first; k < first + count; ++k)
      ++counts[octant(order_[k])];
    int occupied = 0;
    for (int32_t c : counts)
      occupied += c > 0;
    if (occupied <= 1) {
      nodes_[node].first = first;
      nodes_[node].count = count;
      return;
    }
    std::stable_sort(order_.begin() + first, order_.begin() + first + count,
                     [&](int32_t a, int32_t b) { return octant(a) < octant(b); });
    const int32_t child0 = int32_t(nodes_.size());
    nodes_[node].first = child0;
    nodes_[node].count = 0;
    nodes_[node].children = occupied;
    nodes_.resize(nodes_.size() + occupied);
    int32_t start = first, child = child0;
    for (int o = 0; o < 8; ++o) {
      if (counts[o] == 0) continue;
      build(child++, start, counts[o], depth + 1);
      start += counts[o];
    }
  }

  const std::vector<Prim>& prims_;
  std::vector<int32_t> order_;
  std::vector<Node> nodes_;
};

template <class Prim>
DenseGrid<float> octree_distance(glm::ivec3 dims, const std::vector<Prim>& prims, int threads) {
  const Octree<Prim> tree(prims);
  DenseGrid<float> out(dims);
  parallel_for(
      int64_t(dims.z) * dims.y,
      [&](int64_t row) {
        const int y = int(row % dims.y), z = int(row / dims.y);
        int32_t hint = -1;
        for (int x = 0; x < dims.x; ++x) {
          const auto [d2, id] = tree.nearest(glm::vec3(float(x), float(y), float(z)), hint);
          hint = id;
          out.at(x, y, z) = std::sqrt(d2);
        }
      },
      threads);
  return out;
}

}  // namespace

DenseGrid<float> octree_distance_to_points(glm::ivec3 dims, const std::vector<glm::vec3>& points,
                                           int threads) {
  return octree_distance(dims, points, threads);
}

DenseGrid<float> octree_distance_to_triangles(glm::ivec3 dims,
                                              const std::vector<Triangle3>& triangles,
                                              int threads) {
  return octree_distance(dims, triangles, threads);
}

}  // namespace sculpt::core
