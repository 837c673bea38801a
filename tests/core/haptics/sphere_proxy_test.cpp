#include "sculpt/core/haptics/sphere_proxy.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include "sculpt/core/haptics/distance_patch.h"
#include "sculpt/core/haptics/haptic_renderer.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core {
namespace {

constexpr float kCentre = 31.5f;  // of the 64^3 test volumes
constexpr float kRadius = 12.0f;

SphereProxyOptions with_radius(float radius_vox) {
  SphereProxyOptions options;
  options.radius_vox = radius_vox;
  return options;
}

PatchSnapshot patch_of(const Volume& volume, glm::vec3 centre, int edge = 64) {
  // Band for the largest sphere the tests use (radius 3).
  DistancePatch patch({.edge = edge, .band_vox = band_for_sphere(3.0f)});
  patch.build(volume, centre);
  return patch.snapshot();
}

Volume ball() {
  DenseGrid<uint8_t> g(glm::ivec3(64));
  for (int z = 0; z < 64; ++z)
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x)
        g.at(x, y, z) = density_from_distance(glm::length(glm::vec3(x, y, z) - kCentre) - kRadius);
  return Volume::from_dense(g);
}

TEST(SphereProxy, DevicePassingThroughABallLeavesTheProxyOnTheEntrySide) {
  const Volume volume = ball();
  const PatchSnapshot field = patch_of(volume, glm::vec3(kCentre));
  SphereProxy proxy(with_radius(1.0f));
  proxy.reset(field, glm::vec3(kCentre - 20.0f, kCentre, kCentre));
  for (float x = kCentre - 20.0f; x <= kCentre + 14.0f; x += 1.0f) {
    const glm::vec3 device(x, kCentre, kCentre);
    const ProxyState& s = proxy.update(field, device);
    EXPECT_GE(field.sample(s.position_vox).phi_vox, 1.0f - 0.1f) << "device x " << x;
    EXPECT_LT(s.position_vox.x, kCentre - kRadius) << "device x " << x;
    const bool device_inside = glm::length(device - kCentre) < kRadius + 1.0f;
    if (device_inside) {
      EXPECT_TRUE(s.contact) << "device x " << x;
    }
    if (x < kCentre - kRadius - 1.5f) {
      EXPECT_FALSE(s.contact) << "device x " << x;
    }
  }
}

TEST(SphereProxy, AFastDeviceAnywhereInsideNeverPullsTheProxyIn) {
  const Volume volume = ball();
  const PatchSnapshot field = patch_of(volume, glm::vec3(kCentre));
  SphereProxy proxy(with_radius(2.0f));
  proxy.reset(field, glm::vec3(kCentre - 20.0f, kCentre, kCentre));
  uint32_t state = 12345;
  const auto next = [&] {
    return float((state = state * 1664525u + 1013904223u) >> 8) / 16777216.0f;
  };
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 device =
        glm::vec3(kCentre) + 18.0f * (glm::vec3(next(), next(), next()) - 0.5f);
    const ProxyState& s = proxy.update(field, device);
    ASSERT_GE(field.sample(s.position_vox).phi_vox, 2.0f - 0.1f) << "tick " << i;
    ASSERT_GE(glm::length(s.position_vox - kCentre), kRadius + 2.0f - 0.15f) << "tick " << i;
  }
}

TEST(SphereProxy, SlidingBelowTheSurfaceFollowsTheRadialProjection) {
  const Volume volume = ball();
  const PatchSnapshot field = patch_of(volume, glm::vec3(kCentre));
  SphereProxy proxy(with_radius(1.0f));
  const glm::vec3 c(kCentre);
  proxy.reset(field, c + glm::vec3(20.0f, 0.0f, 0.0f));
  for (int i = 0; i <= 400; ++i) {
    const float angle = float(i) * 0.005f;  // a quarter turn, 0.06 voxel a tick at depth
    const glm::vec3 device =
        c + (kRadius - 2.0f) * glm::vec3(std::cos(angle), std::sin(angle), 0.1f);
    const ProxyState& s = proxy.update(field, device);
    if (i < 10) continue;  // the first ticks come in from outside
    const glm::vec3 radial = c + (kRadius + 1.0f) * glm::normalize(device - c);
    EXPECT_LT(glm::length(s.position_vox - radial), 0.15f) << "tick " << i;
    EXPECT_TRUE(s.contact);
  }
}

TEST(SphereProxy, ATwoVoxelPlateCrossedInThreeTicksDoesNotLetThrough) {
  const Volume volume =
      Volume::from_dense(box_density(glm::ivec3(64), glm::vec3(4, 4, 30), glm::vec3(60, 60, 32)));
  const PatchSnapshot field = patch_of(volume, glm::vec3(32.0f));
  for (const float radius : {0.0f, 1.0f, 3.0f}) {
    SphereProxy proxy(with_radius(radius));
    proxy.reset(field, glm::vec3(30, 31, 40));
    for (const float z : {36.0f, 31.0f, 26.0f, 22.0f, 22.0f}) {
      const ProxyState& s = proxy.update(field, glm::vec3(30, 31, z));
      EXPECT_GE(s.position_vox.z, 32.0f + radius - 0.1f) << "radius " << radius << " z " << z;
    }
    EXPECT_TRUE(proxy.state().contact);
    EXPECT_NEAR(proxy.state().position_vox.x, 30.0f, 1e-3f);
  }
}

// The proxy held still against a feature: outside, and the same every tick.
void expect_holds(const PatchSnapshot& field, glm::vec3 start, glm::vec3 device, float radius) {
  SphereProxy proxy(with_radius(radius));
  proxy.reset(field, start);
  for (int i = 0; i < 30; ++i)
    (void)proxy.update(field, start + (device - start) * (float(i) / 29.0f));
  const glm::vec3 rest = proxy.state().position_vox;
  for (int i = 0; i < 50; ++i) {
    const ProxyState& s = proxy.update(field, device);
    EXPECT_GE(field.sample(s.position_vox).phi_vox, radius - 0.1f);
    EXPECT_LT(glm::length(s.position_vox - rest), 1e-3f) << "tick " << i;
    EXPECT_TRUE(s.contact);
  }
}

TEST(SphereProxy, CubeEdgesAndCornersHold) {
  const Volume volume =
      Volume::from_dense(box_density(glm::ivec3(64), glm::vec3(20), glm::vec3(44)));
  const PatchSnapshot field = patch_of(volume, glm::vec3(32.0f));
  // Pressed into a corner along its diagonal, and into an edge across it.
  expect_holds(field, glm::vec3(14.0f), glm::vec3(21.5f), 1.0f);
  expect_holds(field, glm::vec3(14.0f, 14.0f, 32.0f), glm::vec3(21.0f, 21.0f, 32.0f), 1.0f);
  expect_holds(field, glm::vec3(14.0f, 14.0f, 32.0f), glm::vec3(21.0f, 21.0f, 32.0f), 0.0f);
}

TEST(SphereProxy, ConcaveCornerHoldsWithSeveralConstraints) {
  // A floor and two walls: the inside corner of a box room.
  DenseGrid<uint8_t> g = box_density(glm::ivec3(64), glm::vec3(4, 4, 4), glm::vec3(60, 60, 20));
  const DenseGrid<uint8_t> wall_x =
      box_density(glm::ivec3(64), glm::vec3(4, 4, 4), glm::vec3(20, 60, 60));
  const DenseGrid<uint8_t> wall_y =
      box_density(glm::ivec3(64), glm::vec3(4, 4, 4), glm::vec3(60, 20, 60));
  for (size_t i = 0; i < g.size(); ++i)
    g[i] = std::max({g[i], wall_x[i], wall_y[i]});
  const PatchSnapshot field = patch_of(Volume::from_dense(g), glm::vec3(32.0f));
  expect_holds(field, glm::vec3(30.0f), glm::vec3(18.0f), 1.0f);  // into the 3-plane corner
  expect_holds(field, glm::vec3(30.0f, 30.0f, 40.0f), glm::vec3(18.0f, 18.0f, 40.0f), 1.0f);
}

TEST(HapticRenderer, FrictionHoldsTheProxyWithinTheStaticConeThenTrailsAtTheDynamicOne) {
  const Volume volume =
      Volume::from_dense(box_density(glm::ivec3(64), glm::vec3(4, 4, 4), glm::vec3(60, 60, 30)));
  const PatchSnapshot field = patch_of(volume, glm::vec3(32.0f));
  HapticSettings settings;
  settings.proxy.radius_vox = 1.0f;
  settings.proxy.friction = {.static_coefficient = 0.5f, .dynamic_coefficient = 0.3f};
  HapticRenderer renderer(settings);
  double t = 0.0;
  for (float z = 36.0f; z >= 29.0f; z -= 0.25f)
    (void)renderer.tick(field, {32, 32, z}, t += 1e-3);
  int stuck = 0, sliding = 0;
  for (int i = 0; i < 400; ++i) {
    const HapticTick& k = renderer.tick(field, {32.0f + 0.02f * float(i), 32, 29}, t += 1e-3);
    ASSERT_TRUE(k.proxy.contact);
    const float fn = std::abs(k.force_n.z);
    const float ft = std::hypot(k.force_n.x, k.force_n.y);
    if (!k.proxy.sliding) {
      ++stuck;
      EXPECT_LE(ft, 0.5f * fn + 1e-3f) << "tick " << i;
    } else {
      ++sliding;
      EXPECT_NEAR(ft, 0.3f * fn, 0.02f) << "tick " << i;
    }
  }
  EXPECT_GT(stuck, 10);
  EXPECT_GT(sliding, 100);
}

TEST(HapticRenderer, ForceIsTheSpringScaledToTheLimitAndTheSameRunTwice) {
  const Volume volume = ball();
  const PatchSnapshot field = patch_of(volume, glm::vec3(kCentre));
  HapticSettings settings;
  settings.coupling = {.stiffness_n_per_mm = 2.0f, .voxel_mm = 0.5f, .max_force_n = 3.0f};
  const auto run = [&] {
    HapticRenderer renderer(settings);
    std::vector<glm::vec3> forces;
    for (int i = 0; i < 60; ++i) {
      const glm::vec3 device(kCentre + 16.0f - 0.2f * float(i), kCentre + 0.5f, kCentre);
      const HapticTick& k = renderer.tick(field, device, 1e-3 * i);
      forces.push_back(k.force_n);
      const glm::vec3 spring = 2.0f * 0.5f * (k.proxy.position_vox - device);
      const glm::vec3 expected =
          glm::length(spring) > 3.0f ? spring * (3.0f / glm::length(spring)) : spring;
      if (k.proxy.contact) {
        EXPECT_LT(glm::length(k.force_n - expected), 1e-5f) << "tick " << i;
      } else {
        EXPECT_EQ(k.force_n, glm::vec3(0.0f));
      }
      EXPECT_LE(glm::length(k.force_n), 3.0f + 1e-5f);
    }
    return forces;
  };
  const std::vector<glm::vec3> first = run();
  EXPECT_EQ(first, run());
  EXPECT_NEAR(glm::length(first.back()), 3.0f, 1e-5f);
}

TEST(VirtualCoupling, SuddenForceRampsInByTheStepCap) {
  VirtualCoupling coupling({.stiffness_n_per_mm = 1.0f,
                            .voxel_mm = 1.0f,
                            .max_force_n = 8.0f,
                            .max_force_step_n = 1.0f});
  const glm::vec3 n(0, 0, 1);
  EXPECT_NEAR(coupling.force({0, 0, 0}, {0, 0, -5}, true, n, {}).z, 1.0f, 1e-6f);
  EXPECT_NEAR(coupling.force({0, 0, 0}, {0, 0, -5}, true, n, {}).z, 2.0f, 1e-6f);
  // Letting go is never held back.
  EXPECT_EQ(coupling.force({0, 0, 0}, {0, 0, 1}, false, n, {}), glm::vec3(0.0f));
}

TEST(PassivityObserver, AddsDampingOnlyWhenTheContactWouldGiveEnergyBack) {
  PassivityObserver observer(1000.0f);
  // Pushing in against the force stores energy: no damping.
  glm::vec3 f = observer.apply({0, 0, 2}, {0, 0, -0.1f}, 1e-3);
  EXPECT_EQ(f, glm::vec3(0, 0, 2));
  EXPECT_NEAR(observer.energy_j(), 2e-4, 1e-9);
  // A force larger on the way out than on the way in (material edited under
  // the tool) would return more: the observer damps the excess away.
  for (int i = 0; i < 5; ++i)
    f = observer.apply({0, 0, 4}, {0, 0, 0.1f}, 1e-3);
  EXPECT_GE(observer.energy_j(), -1e-12);
  EXPECT_LT(f.z, 4.0f);
  EXPECT_GT(observer.last_damping_ns_per_m(), 0.0f);
}

}  // namespace
}  // namespace sculpt::core
