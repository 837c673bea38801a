#include "sculpt/core/sculpt/inflate_brush.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "brush_test_shapes.h"
#include "sculpt/core/distance/distance_normals.h"

namespace sculpt::core {
namespace {

constexpr int kN = 64;
constexpr float kRadius = 20.0f;
const glm::vec3 kCentre(0.5f * (kN - 1));

// Distance from the centre along `dir` at which the density falls to 127.5.
float radial_height(const DenseGrid<float>& g, glm::vec3 dir) {
  float lo = 0.0f, hi = 0.5f * kN - 1.0f;
  for (int i = 0; i < 40; ++i) {
    const float m = 0.5f * (lo + hi);
    (sample_trilinear(g, kCentre + m * dir) >= 127.5f ? lo : hi) = m;
  }
  return 0.5f * (lo + hi);
}

// The smallest and largest radius over 200 directions spread over the sphere.
std::pair<float, float> radius_range(const Volume& v) {
  const DenseGrid<uint8_t> d = v.to_dense();
  DenseGrid<float> g(d.dims());
  std::copy(d.values().begin(), d.values().end(), g.values().begin());
  float lo = 1e9f, hi = 0.0f;
  for (int i = 0; i < 200; ++i) {
    // A Fibonacci sphere.
    const float z = 1.0f - 2.0f * (static_cast<float>(i) + 0.5f) / 200.0f;
    const float r = std::sqrt(1.0f - z * z), a = 2.39996323f * static_cast<float>(i);
    const float h = radial_height(g, glm::vec3(r * std::cos(a), r * std::sin(a), z));
    lo = std::min(lo, h);
    hi = std::max(hi, h);
  }
  return {lo, hi};
}

// A ball covering the whole sphere, hard, so every surface point weighs alike.
InflateBrushOptions covering(float strength) {
  InflateBrushOptions o;
  o.radius_vox = 30.0f;
  o.hardness = 1.0f;
  o.strength = strength;
  o.distance_vox = 2.0f;
  return o;
}

TEST(InflateBrush, ASphereGrowsByTheDistanceAndStaysRound) {
  Volume v = Volume::from_dense(sphere_density(kN, kRadius / kN));
  const auto [lo0, hi0] = radius_range(v);
  const uint64_t before = v.content_hash();
  Sculptor s(v);
  const StrokeSample at{kCentre, {}};
  EXPECT_GT(inflate_stroke(v, s, std::span(&at, 1), covering(1.0f)), 1000);
  const auto [lo1, hi1] = radius_range(v);
  std::printf("inflate: radius %.3f..%.3f -> %.3f..%.3f\n", lo0, hi0, lo1, hi1);
  EXPECT_NEAR(lo1, lo0 + 2.0f, 0.15f);
  EXPECT_NEAR(hi1, hi0 + 2.0f, 0.15f);
  EXPECT_LE(hi1 - lo1, (hi0 - lo0) + 0.1f);
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(v.content_hash(), before);
}

TEST(InflateBrush, VolumeGrowsMonotonicallyWithStrength) {
  double last = test::mass(Volume::from_dense(sphere_density(kN, kRadius / kN)));
  for (float strength : {0.1f, 0.25f, 0.5f, 0.75f, 1.0f}) {
    Volume v = Volume::from_dense(sphere_density(kN, kRadius / kN));
    Sculptor s(v);
    InflateBrushOptions o = covering(strength);
    o.hardness = 0.5f;
    const StrokeSample at{kCentre + glm::vec3(kRadius, 0.0f, 0.0f), {}};
    (void)inflate_stroke(v, s, std::span(&at, 1), o);
    const double m = test::mass(v);
    EXPECT_GT(m, last) << "strength " << strength;
    last = m;
  }
}

TEST(InflateBrush, AbsurdOptionsAreRefusedByName) {
  InflateBrushOptions o;
  EXPECT_TRUE(check_inflate_brush(o));
  o.distance_vox = 0.0f;
  ASSERT_FALSE(check_inflate_brush(o));
  EXPECT_NE(check_inflate_brush(o).error().message().find("'distance'"), std::string::npos);
  o.distance_vox = 100.0f;
  EXPECT_FALSE(check_inflate_brush(o));
}

}  // namespace
}  // namespace sculpt::core
