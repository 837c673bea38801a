#include "sculpt/core/sculpt/smooth_brush.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core {
namespace {

constexpr int kN = 96;
constexpr float kRadius = 30.0f;
const glm::vec3 kCentre(0.5f * (kN - 1));

// The radius-30 sphere with its density ramp scrambled by up to +-`noise`:
// a surface bumpy at the voxel scale.
Volume noisy_sphere(int noise) {
  DenseGrid<uint8_t> g = sphere_density(kN, kRadius / kN);
  uint32_t s = 12345;
  for (uint8_t& v : g.values()) {
    if (v == 0 || v == 255) continue;
    s = s * 1664525u + 1013904223u;
    const int r = static_cast<int>((s >> 8) % static_cast<uint32_t>(2 * noise + 1)) - noise;
    v = static_cast<uint8_t>(std::clamp(int(v) + r, 1, 254));
  }
  return Volume::from_dense(g);
}

// Mean angle (radians) between the normals of neighbouring vertices, over
// the mesh edges whose ends lie on the band the stroke covers.
double mean_normal_angle(const Volume& v) {
  const Mesh m = marching_cubes(v);
  auto in_band = [](glm::vec3 p) {
    const glm::vec3 r = p - kCentre;
    return std::abs(r.z) < 4.0f && r.x > 0.0f && std::abs(std::atan2(r.y, r.x)) < 0.35f;
  };
  double sum = 0.0;
  int64_t n = 0;
  for (const glm::uvec3& t : m.triangles)
    for (int e = 0; e < 3; ++e) {
      const uint32_t a = t[e], b = t[(e + 1) % 3];
      if (!in_band(m.positions[a]) || !in_band(m.positions[b])) continue;
      const float c = std::clamp(glm::dot(m.normals[a], m.normals[b]), -1.0f, 1.0f);
      sum += std::acos(c);
      ++n;
    }
  EXPECT_GT(n, 500);
  return sum / static_cast<double>(n);
}

double mass(const Volume& v) {
  const DenseGrid<uint8_t> g = v.to_dense();
  double m = 0.0;
  for (uint8_t x : g.values())
    m += x;
  return m / 255.0;
}

int64_t inside(const Volume& v) {
  const DenseGrid<uint8_t> g = v.to_dense();
  int64_t n = 0;
  for (uint8_t x : g.values())
    n += x >= 128;
  return n;
}

// Distance from the centre along `dir` at which the trilinear density of g
// falls to 127.5.
float radial_height(const DenseGrid<uint8_t>& g, glm::vec3 dir) {
  auto sample = [&](float r) {
    const glm::vec3 p = kCentre + r * dir;
    const glm::ivec3 i(glm::floor(p));
    const glm::vec3 f = p - glm::vec3(i);
    float v = 0.0f;
    for (int k = 0; k < 8; ++k) {
      const glm::ivec3 c = i + glm::ivec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
      const float w = ((k & 1) ? f.x : 1.0f - f.x) * (((k >> 1) & 1) ? f.y : 1.0f - f.y) *
                      (((k >> 2) & 1) ? f.z : 1.0f - f.z);
      v += w * g.at(c.x, c.y, c.z);
    }
    return v;
  };
  float lo = kRadius - 3.0f, hi = kRadius + 3.0f;
  for (int i = 0; i < 40; ++i) {
    const float m = 0.5f * (lo + hi);
    (sample(m) >= 127.5f ? lo : hi) = m;
  }
  return 0.5f * (lo + hi);
}

std::vector<StrokeSample> equator_arc() {
  std::vector<StrokeSample> path;
  for (float a = -0.5f; a <= 0.5001f; a += 2.0f / kRadius)
    path.push_back({kCentre + kRadius * glm::vec3(std::cos(a), std::sin(a), 0.0f), {}});
  return path;
}

TEST(SmoothBrush, OneStrokeHalvesTheNormalNoiseAndKeepsTheVolume) {
  Volume v = noisy_sphere(60);
  const double angle_before = mean_normal_angle(v);
  const double mass_before = mass(v);
  const int64_t inside_before = inside(v);
  Sculptor s(v);
  s.set_tool(make_sphere_tool(8.0f));
  SmoothBrushOptions o;
  o.radius_vox = 8.0f;
  const int64_t changed = smooth_stroke(v, s, equator_arc(), o);
  EXPECT_GT(changed, 1000);
  const double angle_after = mean_normal_angle(v);
  EXPECT_LE(angle_after, 0.5 * angle_before) << angle_before << " -> " << angle_after;
  EXPECT_NEAR(mass(v), mass_before, 0.02 * mass_before);
  EXPECT_NEAR(static_cast<double>(inside(v)), static_cast<double>(inside_before),
              0.02 * static_cast<double>(inside_before));
  // One undo step, bit exact.
  const uint64_t after = v.content_hash();
  ASSERT_TRUE(s.undo());
  EXPECT_NEAR(mean_normal_angle(v), angle_before, 1e-9);
  ASSERT_TRUE(s.redo());
  EXPECT_EQ(v.content_hash(), after);
}

TEST(SmoothBrush, AlreadySmoothSurfaceBarelyMoves) {
  Volume v = noisy_sphere(0);
  const DenseGrid<uint8_t> before = v.to_dense();
  Sculptor s(v);
  s.set_tool(make_sphere_tool(8.0f));
  (void)smooth_stroke(v, s, equator_arc(), {});
  const DenseGrid<uint8_t> after = v.to_dense();
  // The blur rounds the density ramp's ends (values there change by tens),
  // but the surface, mid-ramp, moves only by the ball's curvature flow.
  float worst = 0.0f;
  for (float a = -0.3f; a <= 0.3f; a += 0.01f) {
    const glm::vec3 dir(std::cos(a), std::sin(a), 0.0f);
    worst = std::max(worst, std::abs(radial_height(after, dir) - radial_height(before, dir)));
  }
  EXPECT_LE(worst, 0.1f);
}

}  // namespace
}  // namespace sculpt::core
