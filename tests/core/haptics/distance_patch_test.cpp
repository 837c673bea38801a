#include "sculpt/core/haptics/distance_patch.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "sculpt/core/sculpt/sculptor.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core {
namespace {

float trilinear(const DenseGrid<uint8_t>& g, glm::vec3 p) {
  const glm::ivec3 c = glm::ivec3(glm::floor(p));
  const glm::vec3 f = p - glm::vec3(c);
  float v = 0.0f;
  for (int k = 0; k < 8; ++k) {
    const glm::ivec3 o{k & 1, (k >> 1) & 1, k >> 2};
    const glm::ivec3 q = c + o;
    const float w = (o.x ? f.x : 1 - f.x) * (o.y ? f.y : 1 - f.y) * (o.z ? f.z : 1 - f.z);
    v += w * (g.in_bounds(q.x, q.y, q.z) ? float(g.at(q.x, q.y, q.z)) : 0.0f);
  }
  return v;
}

// The radius along unit direction u from `centre` where the trilinear density
// crosses 127.5 (bisection; the shape is star-shaped around its centre).
float iso_radius(const DenseGrid<uint8_t>& g, glm::vec3 centre, glm::vec3 u, float lo, float hi) {
  for (int i = 0; i < 40; ++i) {
    const float mid = 0.5f * (lo + hi);
    (trilinear(g, centre + mid * u) > 127.5f ? lo : hi) = mid;
  }
  return 0.5f * (lo + hi);
}

// Distance from v to the trilinear iso-surface of a near-sphere, by a coarse
// then fine search over directions around the radial one.
float reference_distance(const DenseGrid<uint8_t>& g, glm::vec3 centre, float radius, glm::vec3 v) {
  const glm::vec3 u = glm::normalize(v - centre);
  const glm::vec3 a =
      glm::normalize(glm::cross(u, std::abs(u.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)));
  const glm::vec3 b = glm::cross(u, a);
  glm::vec2 best(0.0f);
  float best_d = 1e9f;
  float span = 0.3f;
  for (int pass = 0; pass < 3; ++pass) {
    const glm::vec2 around = best;
    for (int i = -10; i <= 10; ++i)
      for (int j = -10; j <= 10; ++j) {
        const glm::vec2 t = around + glm::vec2(i, j) * (span / 10.0f);
        const glm::vec3 dir = glm::normalize(u + t.x * a + t.y * b);
        const glm::vec3 s = centre + iso_radius(g, centre, dir, radius - 3, radius + 3) * dir;
        const float d = glm::length(v - s);
        if (d < best_d) best_d = d, best = t;
      }
    span /= 8.0f;
  }
  return trilinear(g, v) > 127.5f ? -best_d : best_d;
}

TEST(DistancePatch, MatchesTheTrilinearIsoSurfaceWithinATenthOfAVoxelInTheBand) {
  const Volume volume = sphere_volume(48, 0.25f);  // radius 12 about (23.5, 23.5, 23.5)
  const DenseGrid<uint8_t> dense = volume.to_dense();
  const glm::vec3 centre(23.5f);
  DistancePatch patch;
  patch.build(volume, centre);
  ASSERT_EQ(patch.box().lo, glm::ivec3(-1));
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> coord(0, 47);
  int checked = 0;
  float worst = 0.0f;
  while (checked < 150) {
    const glm::ivec3 v{coord(rng), coord(rng), coord(rng)};
    const float analytic = glm::length(glm::vec3(v) - centre) - 12.0f;
    if (std::abs(analytic) > 3.8f) continue;
    const float ref = reference_distance(dense, centre, 12.0f, glm::vec3(v));
    const float got = patch.snapshot().at(v);
    worst = std::max(worst, std::abs(got - ref));
    EXPECT_NEAR(got, ref, 0.1f) << "voxel " << v.x << " " << v.y << " " << v.z;
    ++checked;
  }
  RecordProperty("worst_error_vox", std::to_string(worst));
}

TEST(DistancePatch, FarValuesAreClampedBoundsThatNeverExceedTheTrueDistance) {
  const Volume volume = sphere_volume(48, 0.25f);
  DistancePatch patch;
  patch.build(volume, glm::vec3(23.5f));
  const PatchSnapshot& s = patch.snapshot();
  // Seeds are offered within ceil(4 + 0.87) = 5 voxels; beyond, the
  // surface is at least 5 - sqrt(3) - 1 away.
  EXPECT_FLOAT_EQ(s.clamp_vox, 4.0f - std::sqrt(3.0f));
  EXPECT_EQ(s.at({23, 23, 23}), -s.clamp_vox);  // 12 voxels deep
  EXPECT_EQ(s.at({0, 0, 0}), s.clamp_vox);      // 28 voxels out
  for (int x = 0; x < 48; ++x) {
    const float analytic = glm::length(glm::vec3(float(x) - 23.5f, -0.5f, -0.5f)) - 12.0f;
    const float got = s.at({x, 23, 23});
    if (std::abs(analytic) <= 4.0f) {
      EXPECT_NEAR(got, analytic, 0.1f) << x;
    }
    if (std::abs(got) == s.clamp_vox) {
      EXPECT_LE(s.clamp_vox, std::abs(analytic) + 0.1f) << x;
    }
  }
}

TEST(DistancePatch, RefreshedAfterADabEqualsAPatchBuiltFromScratch) {
  Volume volume = sphere_volume(64, 0.3f);
  const glm::vec3 at(31.5f + 19.2f, 31.5f, 31.5f);
  DistancePatch patch;
  patch.build(volume, at);
  (void)volume.take_dirty_bricks();
  Sculptor sculptor(volume);
  sculptor.set_tool(make_sphere_tool(6.0f));
  Dab dab;
  dab.position_vox = at + glm::vec3(-2.0f, 3.0f, 1.0f);
  dab.mode = SculptMode::kSubtract;
  const DabStats stats = sculptor.dab(dab);
  ASSERT_GT(stats.voxels_changed, 0);
  for (const glm::ivec3 b : volume.take_dirty_bricks())
    patch.refresh(volume, volume.brick_box(b));
  DistancePatch fresh;
  fresh.build(volume, at);
  EXPECT_EQ(patch.snapshot().phi, fresh.snapshot().phi);
  EXPECT_GT(patch.snapshot().version, 1u);
}

TEST(DistancePatch, AnySequenceOfDabsAndMovesKeepsTheValuesOfAFreshBuild) {
  // The refresh keeps the seeds a dab left alone and recomputes only the
  // values a changed seed reaches: after every step the patch must hold
  // exactly what one built there from scratch holds.
  Volume volume = sphere_volume(96, 0.3f);
  glm::vec3 centre(47.5f + 28.8f, 47.5f, 47.5f);
  DistancePatch patch;
  patch.build(volume, centre);
  (void)volume.take_dirty_bricks();
  Sculptor sculptor(volume);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> offset(-14.0f, 14.0f), radius(1.5f, 9.0f);
  int64_t partial_refreshes = 0;
  for (int step = 0; step < 14; ++step) {
    if (step % 5 == 4) {
      centre += glm::vec3(offset(rng), offset(rng), offset(rng)) / 3.0f;
      patch.recentre(volume, centre);
    } else {
      Dab dab;
      if (step == 0) {
        // A mound whose middle lies farther than any seed reaches from both
        // the old surface and the new: only its change of side marks it.
        sculptor.set_tool(make_sphere_tool(13.0f));
        dab.position_vox = centre + glm::vec3(8.0f, 0.0f, 0.0f);
      } else {
        sculptor.set_tool(make_sphere_tool(radius(rng)));
        dab.position_vox = centre + glm::vec3(offset(rng), offset(rng), offset(rng));
      }
      dab.mode = step % 2 == 0 ? SculptMode::kAdd : SculptMode::kSubtract;
      (void)sculptor.dab(dab);
      patch.refresh_bricks(volume, volume.take_dirty_bricks());
      const int64_t all = int64_t{48} * 48 * 48;
      if (patch.last_computed_voxels() > 0 && patch.last_computed_voxels() < all)
        ++partial_refreshes;
    }
    DistancePatch fresh;
    fresh.build(volume, centre);
    ASSERT_EQ(patch.box(), fresh.box()) << "step " << step;
    ASSERT_EQ(patch.snapshot().phi, fresh.snapshot().phi) << "step " << step;
  }
  EXPECT_GE(partial_refreshes, 4);
}

TEST(DistancePatch, RecentredEqualsAPatchBuiltThereAndComputesOnlyTheNewPart) {
  const Volume volume = sphere_volume(64, 0.3f);
  DistancePatch patch;
  patch.build(volume, glm::vec3(40.0f, 30.0f, 31.0f));
  const glm::vec3 moved(45.2f, 27.9f, 33.5f);  // origin moves by (5, -3, 2)
  patch.recentre(volume, moved);
  EXPECT_LT(patch.last_computed_voxels(), 48 * 48 * 10);
  DistancePatch fresh;
  fresh.build(volume, moved);
  EXPECT_EQ(patch.box(), fresh.box());
  EXPECT_EQ(patch.snapshot().phi, fresh.snapshot().phi);
}

TEST(DistancePatch, AWideBandGivesTheSameValuesInTheNarrowBand) {
  // Band 8 takes the value-by-value path (reach 9); within 4 voxels it must
  // agree with the sixteen-lane one within 0.1 voxel.
  const Volume volume = sphere_volume(64, 0.3f);
  const glm::vec3 at(31.5f + 19.2f, 31.5f, 31.5f);
  DistancePatch narrow, wide({.edge = 48, .band_vox = 8.0f});
  narrow.build(volume, at);
  wide.build(volume, at);
  ASSERT_EQ(narrow.box(), wide.box());
  int compared = 0;
  for (size_t i = 0; i < narrow.snapshot().phi.size(); ++i) {
    const float a = narrow.snapshot().phi[i], b = wide.snapshot().phi[i];
    // (Voxels with no seed in the narrow reach hold its bound, not a value.)
    if (std::abs(a) > 4.0f || std::abs(a) == narrow.snapshot().clamp_vox) continue;
    EXPECT_NEAR(a, b, 0.1f) << i;
    ++compared;
  }
  EXPECT_GT(compared, 10000);
  EXPECT_GT(wide.snapshot().clamp_vox, 6.0f);
}

TEST(DistancePatch, ThreadsSplitTheWorkButNeverChangeAValue) {
  Volume volume = sphere_volume(64, 0.3f);
  const glm::vec3 at(31.5f + 19.2f, 31.5f, 31.5f);
  DistancePatch one, two({.edge = 48, .band_vox = 4.0f, .threads = 2});
  one.build(volume, at);
  two.build(volume, at);
  EXPECT_EQ(one.snapshot().phi, two.snapshot().phi);
  Sculptor sculptor(volume);
  sculptor.set_tool(make_sphere_tool(8.0f));
  Dab dab;
  dab.position_vox = at;
  dab.mode = SculptMode::kSubtract;
  (void)sculptor.dab(dab);
  const std::vector<glm::ivec3> bricks = volume.take_dirty_bricks();
  one.refresh_bricks(volume, bricks);
  two.refresh_bricks(volume, bricks);
  EXPECT_EQ(one.snapshot().phi, two.snapshot().phi);
}

TEST(DistancePatch, EdgeForReachCoversTheToolAndTheBand) {
  EXPECT_EQ(patch_edge_for_reach(1.0f), 48);
  EXPECT_GE(patch_edge_for_reach(16.0f), 2 * (16 + 4));
  EXPECT_EQ(patch_edge_for_reach(16.0f) % 8, 0);
}

}  // namespace
}  // namespace sculpt::core
