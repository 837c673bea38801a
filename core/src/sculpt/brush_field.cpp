// The ball brushes' shared part (brush_field.h). Each brush reads the
// material under the ball once, before it changes anything, and computes
// every voxel from that copy: the result does not depend on the order the
// voxels are visited in, and the stroke is one external edit, one undo step.

#include "brush_field.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "sculpt/core/distance/distance_normals.h"
#include "sculpt/core/sculpt/capsule_row.h"
#include "sculpt/core/tool/tool.h"
#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core::brush {
namespace {

glm::vec3 segment_closest(glm::vec3 p, glm::vec3 a, glm::vec3 b) {
  const glm::vec3 ab = b - a;
  const float ab2 = glm::dot(ab, ab);
  const float t = ab2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / ab2, 0.0f, 1.0f) : 0.0f;
  return a + t * ab;
}

// out = [1 2 1] / 4 of prev, cur, next, element by element over n floats,
// each as 0.25 prev + 0.5 cur + 0.25 next in that order: any loop order or
// vector width gives the same floats (no fused multiply-adds: baseline x86-64).
void blend_121(float* out, const float* prev, const float* cur, const float* next, int64_t n) {
  for (int64_t i = 0; i < n; ++i)
    out[i] = 0.25f * prev[i] + 0.5f * cur[i] + 0.25f * next[i];
}

// One [1 2 1] / 4 pass along `axis` over g, edges clamped. Along x a row
// at a time from a copy of it; along y (z) a row (slice) at a time, with
// copies of the one before and the one being overwritten: contiguous loops
// the compiler vectorises, no branch per voxel and no copy of the whole grid
// (the smooth brush's blur in the window's path-brush previews was most of
// their time).
void blur_axis(DenseGrid<float>& g, int axis, std::vector<float>& a, std::vector<float>& b) {
  const glm::ivec3 d = g.dims();
  float* v = g.values().data();
  if (axis == 0) {
    const int64_t n = d.x;
    a.resize(static_cast<size_t>(n + 2));
    for (int64_t row = 0; row < int64_t{d.y} * d.z; ++row) {
      float* r = v + row * n;
      std::copy(r, r + n, a.begin() + 1);
      a[0] = a[1];  // clamped: the edge's neighbour beyond it is itself
      a[static_cast<size_t>(n + 1)] = a[static_cast<size_t>(n)];
      blend_121(r, a.data(), a.data() + 1, a.data() + 2, n);
    }
    return;
  }
  // Rows (axis 1) or slices (axis 2) of `len` floats, `count` of them in a
  // block, `blocks` blocks.
  const int64_t len = axis == 1 ? d.x : int64_t{d.x} * d.y;
  const int64_t count = axis == 1 ? d.y : d.z;
  const int64_t blocks = axis == 1 ? d.z : 1;
  a.resize(static_cast<size_t>(len));  // the one before, as it was
  b.resize(static_cast<size_t>(len));  // this one, as it was
  for (int64_t blk = 0; blk < blocks; ++blk) {
    float* base = v + blk * len * count;
    for (int64_t k = 0; k < count; ++k) {
      float* cur = base + k * len;
      std::copy(cur, cur + len, b.begin());
      const float* prev = k > 0 ? a.data() : b.data();
      const float* next = k + 1 < count ? cur + len : b.data();
      blend_121(cur, prev, b.data(), next, len);
      a.swap(b);
    }
  }
}

// std::round(value) clamped to 0..255, as a byte: the same byte for every
// float (clamping first rounds the same way for any value it moves, and
// within 0..255 a float's fraction is exact), without the library call
// std::round() is on plain x86-64.
uint8_t round_to_byte(float value) {
  const float c = std::clamp(value, 0.0f, 255.0f);
  const int whole = static_cast<int>(c);
  return static_cast<uint8_t>(whole + (c - static_cast<float>(whole) >= 0.5f ? 1 : 0));
}

}  // namespace

float Ball::weight(float distance_vox) const {
  if (distance_vox >= reach()) return 0.0f;
  return strength * tool_density(distance_vox - radius_vox, radius_vox, hardness) / 255.0f;
}

Status check_range(const char* key, double value, double lo, double hi) {
  if (value >= lo && value <= hi) return {};
  std::ostringstream s;
  s << "'" << key << "' must be a number in [" << lo << ", " << hi << "], got " << value;
  return Error(s.str());
}

Status check_positive(const char* key, double value, double hi) {
  if (value > 0.0 && value <= hi) return {};
  std::ostringstream s;
  s << "'" << key << "' must be a number in (0, " << hi << "] voxels, got " << value;
  return Error(s.str());
}

Status check_ball(const Ball& ball) {
  if (Status st = check_positive("radius", ball.radius_vox, kMaxBrushRadiusVox); !st) return st;
  if (Status st = check_range("hardness", ball.hardness, 0.0, 1.0); !st) return st;
  return check_range("strength", ball.strength, 0.0, 1.0);
}

PathDistance::PathDistance(std::span<const StrokeSample> path, const Box& box, float reach,
                           bool nearest_points)
    : path_(path),
      box_(box),
      distance_(box.size(), std::numeric_limits<float>::infinity()),
      segment_(nearest_points ? box.size() : glm::ivec3(0), 0) {
  assert(!path.empty());
  const float reach2 = reach * reach;
  std::vector<float> row_lo, row_hi;
  // The first point, then each segment, a voxel taking a segment only when
  // strictly nearer: the nearest point is the first of the path's nearest.
  // Each measures only the rows' stretches its capsule reaches (widened by
  // a voxel against rounding), not its whole box: a diagonal segment as
  // long as the ball is wide reaches under half its box's voxels.
  for (size_t i = 0; i < path.size(); ++i) {
    const glm::vec3 a = path[i == 0 ? 0 : i - 1].position_vox;
    const glm::vec3 b = path[i].position_vox;
    const Box reached = intersect(Box{glm::ivec3(glm::floor(glm::min(a, b) - reach)),
                                      glm::ivec3(glm::ceil(glm::max(a, b) + reach)) + 1},
                                  box_);
    if (reached.empty()) continue;
    const glm::vec3 ab = b - a;
    const float ab2 = glm::dot(ab, ab);
    const int ny = reached.hi.y - reached.lo.y;
    row_lo.resize(static_cast<size_t>(ny));
    row_hi.resize(static_cast<size_t>(ny));
    const auto x_lo = static_cast<float>(reached.lo.x), x_hi = static_cast<float>(reached.hi.x);
    for (int z = reached.lo.z; z < reached.hi.z; ++z) {
      capsule_rows(a, ab, ab2, reached.lo.y, ny, static_cast<float>(z), reach2, true, row_lo.data(),
                   row_hi.data());
      for (int y = reached.lo.y; y < reached.hi.y; ++y) {
        const float lo = row_lo[static_cast<size_t>(y - reached.lo.y)];
        const float hi = row_hi[static_cast<size_t>(y - reached.lo.y)];
        if (lo > hi) continue;
        const int x0 = std::max(reached.lo.x, floor_int(std::max(lo, x_lo - 1.0f)) - 1);
        const int x1 = std::min(reached.hi.x, ceil_int(std::min(hi, x_hi + 1.0f)) + 2);
        for (int x = x0; x < x1; ++x) {
          const glm::vec3 p(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
          const float d = glm::length(p - segment_closest(p, a, b));
          if (d >= reach) continue;
          const glm::ivec3 q = glm::ivec3(x, y, z) - box_.lo;
          const size_t k = distance_.index(q.x, q.y, q.z);
          if (d < distance_[k]) {
            distance_[k] = d;
            if (nearest_points) segment_[k] = static_cast<int32_t>(i);
          }
        }
      }
    }
  }
}

const float* PathDistance::row(int y, int z) const {
  return &distance_.values()[distance_.index(0, y, z)];
}

float PathDistance::at(glm::ivec3 v) const {
  const glm::ivec3 q = v - box_.lo;
  return distance_.at(q.x, q.y, q.z);
}

glm::vec3 PathDistance::closest(glm::ivec3 v) const {
  assert(segment_.dims() == distance_.dims());  // nearest_points asked
  const glm::ivec3 q = v - box_.lo;
  const auto i = static_cast<size_t>(segment_.at(q.x, q.y, q.z));
  return segment_closest(glm::vec3(v), path_[i == 0 ? 0 : i - 1].position_vox,
                         path_[i].position_vox);
}

Box path_box(std::span<const StrokeSample> path, float reach) {
  assert(!path.empty());
  glm::vec3 lo = path[0].position_vox, hi = lo;
  for (const StrokeSample& s : path) {
    lo = glm::min(lo, s.position_vox);
    hi = glm::max(hi, s.position_vox);
  }
  return Box{glm::ivec3(glm::floor(lo - reach)), glm::ivec3(glm::ceil(hi + reach)) + 1};
}

Box reach_box(const Volume& volume, std::span<const StrokeSample> path, const Ball& ball) {
  return intersect(path_box(path, ball.reach()), Box{glm::ivec3(0), volume.dims()});
}

void blur(DenseGrid<float>& g, int passes) {
  std::vector<float> a, b;
  for (int k = 0; k < passes; ++k)
    for (int axis = 0; axis < 3; ++axis)
      blur_axis(g, axis, a, b);
}

Field::Field(const Volume& volume, const Box& box, int margin)
    : box_(intersect(Box{box.lo - margin, box.hi + margin}, Box{glm::ivec3(0), volume.dims()})) {
  const DenseGrid<uint8_t> g = volume.read(box_, 0);
  grid_ = DenseGrid<float>(g.dims());
  std::copy(g.values().begin(), g.values().end(), grid_.values().begin());
}

float Field::at(glm::ivec3 v) const {
  const glm::ivec3 q = v - box_.lo;
  return grid_.at(q.x, q.y, q.z);
}

float Field::sample(glm::vec3 p) const {
  return sample_trilinear(grid_, p - glm::vec3(box_.lo));
}

glm::vec3 Field::gradient(glm::vec3 p) const {
  return distance_gradient(grid_, p - glm::vec3(box_.lo));
}

float Plane::distance(glm::vec3 p) const {
  return glm::dot(p - point, normal);
}

float Plane::density(glm::ivec3 v) const {
  return tool_density(distance(glm::vec3(v)), 1.0f, 1.0f);
}

bool fit_plane(const Field& field, std::span<const StrokeSample> path, const Ball& ball,
               Plane& plane) {
  const Box region = intersect(path_box(path, ball.reach()), field.box());
  const PathDistance distance(path, region, ball.reach());
  glm::dvec3 normal(0.0), centroid(0.0);
  double mass = 0.0;
  for (int z = region.lo.z; z < region.hi.z; ++z)
    for (int y = region.lo.y; y < region.hi.y; ++y)
      for (int x = region.lo.x; x < region.hi.x; ++x) {
        const glm::vec3 p(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
        // The plane's fit ignores the strength: a weak stroke flattens
        // toward the same plane, less far.
        const float d = distance.at(glm::ivec3(x, y, z));
        if (d >= ball.reach()) continue;
        const float w = tool_density(d - ball.radius_vox, ball.radius_vox, ball.hardness) / 255.0f;
        const glm::vec3 g = field.gradient(p);
        const float m = w * glm::length(g);
        if (m <= 0.0f) continue;
        normal -= glm::dvec3(w * g);
        centroid += glm::dvec3(p) * static_cast<double>(m);
        mass += m;
      }
  if (mass <= 0.0 || glm::length(normal) <= 0.0) return false;
  plane.normal = glm::vec3(glm::normalize(normal));
  plane.point = glm::vec3(centroid / mass);
  return true;
}

void side_by_side(const std::function<void()>& a, const std::function<void()>& b) {
  parallel_for(2, [&](int64_t i) { i == 0 ? a() : b(); });
}

int64_t write(Volume& volume, Sculptor& sculptor, const Field& before, const Box& region,
              std::span<const StrokeSample> path, const Ball& ball,
              const std::function<float(glm::ivec3 v, float w, const PathDistance& path)>& value) {
  if (region.empty()) return 0;
  return write(volume, sculptor, before, region, PathDistance(path, region, ball.reach()), ball,
               value);
}

int64_t write(Volume& volume, Sculptor& sculptor, const Field& before, const Box& region,
              const PathDistance& distance, const Ball& ball,
              const std::function<float(glm::ivec3 v, float w, const PathDistance& path)>& value) {
  assert(&sculptor.volume() == &volume);
  if (region.empty()) return 0;
  // The result starts from `before`, not from the volume: a preview that
  // re-brushes part of a longer path finds its last result there. Row by
  // row through pointers: the voxels' index arithmetic was most of this loop.
  const glm::ivec3 n = region.hi - region.lo;
  DenseGrid<uint8_t> out(n);
  const DenseGrid<float>& material = before.grid();
  const glm::ivec3 at_before = region.lo - before.box().lo;
  const float reach = ball.reach();
  // Slices of the box on every core (value() only reads): each writes its
  // own rows of `out` and counts its own changes.
  std::vector<int64_t> changed_in(static_cast<size_t>(n.z), 0);
  parallel_for(n.z, [&](int64_t slice) {
    const auto z = static_cast<int>(slice);
    int64_t changed = 0;
    for (int y = 0; y < n.y; ++y) {
      const float* m =
          &material.values()[material.index(at_before.x, at_before.y + y, at_before.z + z)];
      const float* d = distance.row(y, z);
      uint8_t* o = &out.values()[out.index(0, y, z)];
      for (int x = 0; x < n.x; ++x) {
        const auto was = static_cast<uint8_t>(m[x]);
        o[x] = was;
        if (d[x] >= reach) continue;
        const float w = ball.weight(d[x]);
        if (w <= 0.0f) continue;
        const uint8_t r = round_to_byte(value(region.lo + glm::ivec3(x, y, z), w, distance));
        if (r == was) continue;
        ++changed;
        o[x] = r;
      }
    }
    changed_in[static_cast<size_t>(slice)] = changed;
  });
  const int64_t changed = std::accumulate(changed_in.begin(), changed_in.end(), int64_t{0});
  if (changed == 0) return 0;
  sculptor.external_edit(region, [&] { volume.write(region.lo, out); });
  return changed;
}

}  // namespace sculpt::core::brush
