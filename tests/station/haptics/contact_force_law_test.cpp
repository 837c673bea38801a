// The haptic loop closed through the simulated arm (DESIGN.md §5a): the
// station's contact law on a real distance patch, the hal loop and its safety
// rules, the arm with its force limit, encoder steps and one tick of delay,
// all in virtual time at 1 kHz, at the Falcon's maximum stiffness.
#include "sculpt/station/haptics/contact_force_law.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "sculpt/core/haptics/distance_patch.h"
#include "sculpt/core/shapes/analytic_shapes.h"
#include "sculpt/core/volume/volume.h"
#include "sculpt/hal/force/sim_arm.h"
#include "sculpt/hal/haptics/haptic_loop.h"

namespace sculpt::station {
namespace {

constexpr int64_t kMs = 1'000'000;
constexpr float kFloorY = 32.0f;  // material below, voxels
constexpr float kToolRadiusVox = 2.0f;

core::Volume floor_volume() {
  core::DenseGrid<uint8_t> g(glm::ivec3(64));
  for (int z = 0; z < 64; ++z)
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x)
        g.at(x, y, z) = core::density_from_distance(static_cast<float>(y) - kFloorY);
  return core::Volume::from_dense(g);
}

struct Tick {
  hal::HapticTickRecord loop;
  ContactRecord contact;
  double energy_j = 0.0;
};

// The hand rests, then from 0.5 s pushes the grip 10 mm down (the floor is
// 3 mm below the start) and holds there; 1.5 s in all.
// damping_ns_per_m < 0: the station's default contact damping.
std::vector<Tick> press_on_the_floor(float stiffness_n_per_mm, float damping_ns_per_m = -1.0f) {
  const core::Volume volume = floor_volume();
  core::DistancePatch patch({.edge = 32, .band_vox = core::band_for_sphere(kToolRadiusVox)});
  patch.build(volume, glm::vec3(32.0f, kFloorY + 2.0f, 32.0f));
  core::PatchExchange exchange(patch.options().edge);
  core::copy_snapshot(patch.snapshot(), exchange.back());
  exchange.publish();

  hal::HandScript hand;
  hand.stiffness_n_per_mm = 1.0f;
  hand.damping_ns_per_m = 4.0f;
  hand.path = {{0.0, glm::vec3(0.0f)}, {0.5, glm::vec3(0.0f)}, {0.6, glm::vec3(0, -10, 0)}};
  hal::SimArm arm(hand);

  ContactSettings settings;
  settings.haptic.proxy.radius_vox = kToolRadiusVox;
  settings.haptic.coupling.stiffness_n_per_mm = stiffness_n_per_mm;
  if (damping_ns_per_m >= 0.0f) settings.haptic.coupling.damping_ns_per_m = damping_ns_per_m;
  settings.voxel_mm = 0.5f;
  ContactForceLaw law(exchange, arm.limits(), settings, glm::vec3(32.0f, 40.0f, 32.0f));
  hal::HapticLoop loop(arm, law);
  loop.enable();

  std::vector<Tick> ticks;
  for (int64_t t = 0; t < 1500 * kMs; t += kMs) {
    EXPECT_TRUE(loop.tick(t));
    Tick tick;
    EXPECT_TRUE(loop.records().try_pop(tick.loop));
    EXPECT_TRUE(law.contacts().try_pop(tick.contact));
    tick.energy_j = law.renderer().passivity_energy_j();
    ticks.push_back(tick);
  }
  return ticks;
}

TEST(ContactForceLaw, AtTheFalconsMaximumStiffnessAContactSettlesWithin300msAndStaysPassive) {
  const hal::ForceLimits& limits = hal::sim_arm_limits();
  const std::vector<Tick> ticks = press_on_the_floor(limits.max_stiffness_n_per_mm);
  const auto first_contact =
      std::find_if(ticks.begin(), ticks.end(), [](const Tick& t) { return t.contact.contact; });
  ASSERT_NE(first_contact, ticks.end());
  const size_t contact_tick = static_cast<size_t>(first_contact - ticks.begin());
  EXPECT_GT(contact_tick, 500u);  // the hand starts pushing at 0.5 s
  EXPECT_LT(contact_tick, 700u);

  // The force it settles to: the mean over the last 200 ms.
  double settled = 0.0;
  for (size_t i = ticks.size() - 200; i < ticks.size(); ++i)
    settled += ticks[i].loop.force_n.y;
  settled /= 200.0;
  // The hand's 1 N/mm spring against the wall's 3 N/mm, 7 mm apart: 5.25 N
  // (less the ~0.1 mm the arm's friction and encoder leave).
  EXPECT_NEAR(settled, 5.25, 0.3);

  const double band = std::max(0.05 * settled, 0.1);
  double previous_window = 1e9;
  for (size_t i = contact_tick; i < ticks.size(); ++i) {
    const Tick& t = ticks[i];
    // Never above the device's limit, never an energy the hand did not put in.
    EXPECT_LE(glm::length(t.loop.force_n), limits.max_force_n + 1e-4f) << i;
    EXPECT_GE(t.energy_j, -1e-9) << i;
    if (i >= contact_tick + 300) {
      EXPECT_NEAR(t.loop.force_n.y, settled, band) << "tick " << i << ": not settled";
    }
  }
  // No growing oscillation: the largest departure from the settled force in
  // each 50 ms after contact never grows.
  for (size_t start = contact_tick; start + 50 <= ticks.size(); start += 50) {
    double worst = 0.0;
    for (size_t i = start; i < start + 50; ++i)
      worst = std::max(worst, std::abs(ticks[i].loop.force_n.y - settled));
    EXPECT_LE(worst, previous_window + 0.05) << "window from tick " << start;
    previous_window = worst;
  }
  // The proxy stays on the floor while the device presses into it.
  const Tick& last = ticks.back();
  EXPECT_TRUE(last.contact.contact);
  EXPECT_NEAR(last.contact.proxy_vox.y, kFloorY + kToolRadiusVox, 0.1f);
  EXPECT_LT(last.contact.device_vox.y, last.contact.proxy_vox.y - 2.0f);
}

TEST(ContactForceLaw, WithoutContactDampingTheSamePressStillRingsAfter300ms) {
  // What the default damping is for: the arm's one tick of delay takes about
  // 4.5 N·s/m of damping away from a 3 N/mm wall, and with only the hand's
  // and the mechanism's left the contact rings at about 33 Hz.
  const std::vector<Tick> ticks = press_on_the_floor(3.0f, 0.0f);
  const auto first_contact =
      std::find_if(ticks.begin(), ticks.end(), [](const Tick& t) { return t.contact.contact; });
  ASSERT_NE(first_contact, ticks.end());
  const size_t from = static_cast<size_t>(first_contact - ticks.begin()) + 300;
  float lo = 1e9f, hi = -1e9f;
  for (size_t i = from; i < from + 50; ++i) {
    lo = std::min(lo, ticks[i].loop.force_n.y);
    hi = std::max(hi, ticks[i].loop.force_n.y);
  }
  EXPECT_GT(hi - lo, 1.0f);
}

TEST(ContactForceLaw, VirtualTimeRunsAreIdenticalBitForBit) {
  const std::vector<Tick> a = press_on_the_floor(2.0f);
  const std::vector<Tick> b = press_on_the_floor(2.0f);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].loop.position_mm, b[i].loop.position_mm) << i;
    ASSERT_EQ(a[i].loop.force_n, b[i].loop.force_n) << i;
    ASSERT_EQ(a[i].contact.proxy_vox, b[i].contact.proxy_vox) << i;
  }
}

TEST(ContactForceLaw, SettingsAreClampedToTheDeviceAndTheClutchHoldsTheTool) {
  core::PatchExchange exchange(8);
  ContactSettings wild;
  wild.haptic.coupling.stiffness_n_per_mm = 50.0f;
  wild.haptic.coupling.damping_ns_per_m = 500.0f;
  wild.haptic.coupling.max_force_n = 100.0f;
  wild.workspace_scale = 4.0f;
  wild.force_scale = 7.0f;
  ContactForceLaw law(exchange, hal::sim_arm_limits(), wild, glm::vec3(10.0f));
  EXPECT_FLOAT_EQ(law.settings().haptic.coupling.stiffness_n_per_mm, 3.0f);
  EXPECT_FLOAT_EQ(law.settings().haptic.coupling.damping_ns_per_m, 20.0f);
  EXPECT_FLOAT_EQ(law.settings().haptic.coupling.max_force_n, 8.0f);
  EXPECT_FLOAT_EQ(law.settings().haptic.coupling.voxel_mm, 0.125f);
  EXPECT_FLOAT_EQ(law.settings().force_scale, 1.0f);

  // No patch yet: no force, and the tool follows the device (4 x scale, 0.5 mm voxels).
  hal::HapticInput in;
  in.device.position_mm = {1.0f, 0.0f, 0.0f};
  EXPECT_EQ(law.force_n(in), glm::vec3(0.0f));
  ContactRecord r;
  ASSERT_TRUE(law.contacts().try_pop(r));
  EXPECT_EQ(r.device_vox, glm::vec3(18.0f, 10.0f, 10.0f));
  // Clutched, the device moves 2 mm and the tool stays; released, it moves on from there.
  law.set_clutch(true);
  in.device.position_mm = {3.0f, 0.0f, 0.0f};
  law.force_n(in);
  ASSERT_TRUE(law.contacts().try_pop(r));
  EXPECT_TRUE(r.clutched);
  EXPECT_EQ(r.device_vox, glm::vec3(18.0f, 10.0f, 10.0f));
  law.set_clutch(false);
  in.device.position_mm = {3.5f, 0.0f, 0.0f};
  law.force_n(in);
  ASSERT_TRUE(law.contacts().try_pop(r));
  EXPECT_EQ(r.device_vox, glm::vec3(22.0f, 10.0f, 10.0f));
}

}  // namespace
}  // namespace sculpt::station
