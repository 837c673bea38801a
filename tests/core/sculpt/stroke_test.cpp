#include "sculpt/core/sculpt/stroke.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <thread>
#include <utility>
#include <vector>

#include "sculpt/core/shapes/analytic_shapes.h"
#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

// A slab of material: full below z = top (voxel units), the 2-voxel ramp at top.
Volume slab_volume(glm::ivec3 dims, float top) {
  DenseGrid<uint8_t> g(dims);
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x)
        g.at(x, y, z) = density_from_distance(static_cast<float>(z) - top);
  return Volume::from_dense(g);
}

// Where column (x, y) of `g`, read downward from z_from (empty there),
// first reaches the 127.5 level, linearly interpolated.
float floor_height(const DenseGrid<uint8_t>& g, int x, int y, int z_from) {
  for (int z = z_from; z > 0; --z) {
    const float above = g.at(x, y, z), below = g.at(x, y, z - 1);
    if (above < 127.5f && below >= 127.5f) {
      return static_cast<float>(z - 1) + (below - 127.5f) / (below - above);
    }
  }
  return -1.0f;
}

// Path samples every `spacing` voxels from a to b, b included.
std::vector<StrokeSample> straight_path(glm::vec3 a, glm::vec3 b, float spacing) {
  std::vector<StrokeSample> path;
  const float length = glm::length(b - a);
  const int n = static_cast<int>(std::ceil(length / spacing));
  for (int i = 0; i <= n; ++i) {
    const float t = std::min(1.0f, static_cast<float>(i) * spacing / length);
    path.push_back({glm::mix(a, b, t), glm::quat(1, 0, 0, 0)});
  }
  return path;
}

struct Groove {
  float ripple;      // max - min of the floor along the middle of the groove
  float worst_miss;  // largest |floor - where the ball's bottom passed|
};

// The groove of a radius-`r` ball pulled along x at height path_z over a slab
// whose top is at 30: by a stroke, or (dabs = true) by a dab per sample.
constexpr glm::ivec3 kSlab{112, 48, 48};
constexpr float kTop = 30.0f, kPathY = 24.0f, kPathZ = 34.3f;

Groove cut_groove(float r, float spacing, bool dabs, Volume* out = nullptr, float path_z = kPathZ) {
  Volume v = slab_volume(kSlab, kTop);
  Sculptor s(v);
  s.set_tool(make_sphere_tool(r));
  const auto path = straight_path({10.0f, kPathY, path_z}, {100.0f, kPathY, path_z}, spacing);
  if (dabs) {
    s.begin_stroke();
    for (const StrokeSample& p : path)
      (void)s.dab({p.position_vox, p.orientation, SculptMode::kSubtract, 1.0f});
    s.end_stroke();
  } else {
    (void)sweep_stroke(s, path, {SculptMode::kSubtract, 1.0f, false});
  }
  const DenseGrid<uint8_t> g = v.to_dense();
  float lo = 1e9f, hi = -1e9f, miss = 0.0f;
  for (int x = 30; x <= 80; ++x) {
    const float f = floor_height(g, x, static_cast<int>(kPathY), static_cast<int>(path_z));
    lo = std::min(lo, f);
    hi = std::max(hi, f);
    miss = std::max(miss, std::abs(f - (path_z - r)));
  }
  if (out != nullptr) *out = std::move(v);
  return {hi - lo, miss};
}

TEST(SweptStroke, GrooveFloorIsFlatAtAnySpacingUpToTheRadius) {
  for (float r : {8.0f, 12.5f}) {
    for (float spacing : {0.5f, 1.0f, 2.0f, 0.5f * r, 0.75f * r, r}) {
      const Groove g = cut_groove(r, spacing, false);
      EXPECT_LE(g.ripple, 0.02f) << "radius " << r << ", spacing " << spacing;
      EXPECT_LE(g.worst_miss, 0.1f) << "radius " << r << ", spacing " << spacing;
    }
  }
}

// Off the grid: a groove cut diagonally across the voxels. Each column's floor
// lies where the ball's bottom passed over it (z - sqrt(r^2 - e^2) at lateral
// offset e), so the floor's error from that is what ripples.
Groove cut_diagonal_groove(float r, float spacing, bool dabs) {
  Volume v = slab_volume(kSlab, kTop);
  Sculptor s(v);
  s.set_tool(make_sphere_tool(r));
  const glm::vec3 a{10.0f, 14.3f, kPathZ}, b{100.0f, 33.9f, kPathZ};
  const auto path = straight_path(a, b, spacing);
  if (dabs) {
    s.begin_stroke();
    for (const StrokeSample& p : path)
      (void)s.dab({p.position_vox, p.orientation, SculptMode::kSubtract, 1.0f});
    s.end_stroke();
  } else {
    (void)sweep_stroke(s, path, {SculptMode::kSubtract, 1.0f, false});
  }
  const DenseGrid<uint8_t> g = v.to_dense();
  const glm::vec2 dir = glm::normalize(glm::vec2(b - a));
  float lo = 1e9f, hi = -1e9f, miss = 0.0f;
  for (int x = 30; x <= 80; ++x)
    for (int y = 0; y < kSlab.y; ++y) {
      const glm::vec2 rel = glm::vec2(x, y) - glm::vec2(a);
      const float e = std::abs(rel.x * dir.y - rel.y * dir.x);
      if (e > 2.0f) continue;  // the floor's flat middle
      const float err =
          floor_height(g, x, y, static_cast<int>(kPathZ)) - (kPathZ - std::sqrt(r * r - e * e));
      lo = std::min(lo, err);
      hi = std::max(hi, err);
      miss = std::max(miss, std::abs(err));
    }
  return {hi - lo, miss};
}

// Measured: the stroke's ripple 0.0076 and error 0.008 voxel at spacings 1, 4
// and 8; dabs at spacing 4 (the station's): ripple 0.22, error 0.32.
TEST(SweptStroke, DiagonalGrooveFloorIsWhereTheBallPassed) {
  for (float spacing : {1.0f, 4.0f, 8.0f}) {
    const Groove g = cut_diagonal_groove(8.0f, spacing, false);
    EXPECT_LE(g.ripple, 0.02f) << "spacing " << spacing;
    EXPECT_LE(g.worst_miss, 0.1f) << "spacing " << spacing;
  }
  EXPECT_GT(cut_diagonal_groove(8.0f, 4.0f, true).ripple, 0.2f);
}

// The figures before swept strokes (issue 21), kept as the measure of what a
// stroke fixes: dabs of a radius-8 ball at the station's spacing (a quarter
// of the diameter, half the radius) leave a floor rippled by 0.24 voxel (the
// issue's figure; 0.227 in this groove), its floor up to 0.33 voxel off the
// ball's path. The stroke's: ripple below 0.02, within 0.1 voxel.
TEST(SweptStroke, DabsAtTheStationsSpacingLeaveTheRippleStrokesRemove) {
  const Groove dabs = cut_groove(8.0f, 4.0f, true);
  EXPECT_GT(dabs.ripple, 0.2f);
  EXPECT_GT(dabs.worst_miss, 0.3f);
  const Groove stroke = cut_groove(8.0f, 4.0f, false);
  EXPECT_LT(stroke.ripple, dabs.ripple / 10.0f);
}

TEST(SweptStroke, GrooveWallsKeepASingleDabsDensityRamp) {
  // The ball's path at a whole voxel, where a dab reads its tool's voxels
  // exactly (off the grid it blurs them by its trilinear sampling; the sweep
  // evaluates the ball's own ramp wherever it passes).
  constexpr float kZ = 34.0f;
  Volume stroke_v(glm::ivec3(1), 0);
  (void)cut_groove(8.0f, 4.0f, false, &stroke_v, kZ);
  const DenseGrid<uint8_t> stroke = stroke_v.to_dense();
  // One dab at x = 56, cut into the same slab: across the groove's middle
  // (the plane x = 56) a long capsule's section is the ball's.
  Volume dab_v = slab_volume(kSlab, kTop);
  Sculptor s(dab_v);
  s.set_tool(make_sphere_tool(8.0f));
  (void)s.dab({{56.0f, kPathY, kZ}, glm::quat(1, 0, 0, 0), SculptMode::kSubtract, 1.0f});
  const DenseGrid<uint8_t> dab = dab_v.to_dense();
  int partial = 0, worst = 0;
  for (int z = 0; z < kSlab.z; ++z)
    for (int y = 0; y < kSlab.y; ++y) {
      const int a = stroke.at(56, y, z), b = dab.at(56, y, z);
      worst = std::max(worst, std::abs(a - b));
      partial += a > 0 && a < 255 && z < static_cast<int>(kTop) - 1;
    }
  EXPECT_LE(worst, 1);
  // The wall below the slab's own rim keeps its ramp: no pure 0/255 wall.
  EXPECT_GT(partial, 20);
  // Dabs at the same spacing use the ramp up: a voxel gets the rim of
  // several dabs, so the wall between them holds fewer partial densities
  // than the stroke's.
  Volume dabs_v(glm::ivec3(1), 0);
  (void)cut_groove(8.0f, 4.0f, true, &dabs_v, kZ);
  const DenseGrid<uint8_t> dabs = dabs_v.to_dense();
  int stroke_partial = 0, dabs_partial = 0;
  for (int x = 30; x < 80; ++x)
    for (int z = 0; z < static_cast<int>(kTop) - 1; ++z)
      for (int y = 0; y < kSlab.y; ++y) {
        stroke_partial += stroke.at(x, y, z) > 0 && stroke.at(x, y, z) < 255;
        dabs_partial += dabs.at(x, y, z) > 0 && dabs.at(x, y, z) < 255;
      }
  EXPECT_GT(stroke_partial, dabs_partial);
}

TEST(SweptStroke, StraightStrokeDoesNotDependOnSpacing) {
  Volume fine(glm::ivec3(1), 0), coarse(glm::ivec3(1), 0);
  (void)cut_groove(8.0f, 0.7f, false, &fine);
  (void)cut_groove(8.0f, 8.0f, false, &coarse);
  const DenseGrid<uint8_t> a = fine.to_dense(), b = coarse.to_dense();
  int worst = 0;
  for (size_t i = 0; i < a.size(); ++i)
    worst = std::max(worst, std::abs(int(a[i]) - int(b[i])));
  EXPECT_LE(worst, 1);
}

// A sculptor asked to hands over the voxels of every brick its strokes
// store, of the version stored, byte for byte what decoding gives; one not
// asked keeps none.
TEST(SweptStroke, HandsOverTheVoxelsItStoredWhenAsked) {
  for (const bool asked : {false, true}) {
    Volume v = sphere_volume(128, 0.3f);
    SculptorOptions options;
    options.hand_over_voxels = asked;
    Sculptor sculptor(v, options);
    sculptor.set_tool(make_sphere_tool(12.0f));
    const std::vector<StrokeSample> path = {
        {glm::vec3(64.0f, 64.0f, 64.0f + 38.0f), glm::quat(1, 0, 0, 0)},
        {glm::vec3(80.0f, 64.0f, 64.0f + 34.0f), glm::quat(1, 0, 0, 0)}};
    const DabStats stats = sweep_stroke(sculptor, path, {SculptMode::kSubtract, 1.0f, false});
    ASSERT_GT(stats.bricks_changed, 0);
    const StoredVoxelsByBrick handed = sculptor.take_stored_voxels();
    if (!asked) {
      EXPECT_TRUE(handed.empty());
      continue;
    }
    EXPECT_EQ(static_cast<int>(handed.size()), stats.bricks_changed);
    const int e = v.brick_edge();
    std::vector<uint8_t> decoded(static_cast<size_t>(e) * e * e);
    for (const auto& [index, stored] : handed) {
      const glm::ivec3 b = grid_position(index, v.brick_grid());
      EXPECT_EQ(stored.version, v.brick_version(b));
      v.decode_brick(b, decoded);
      EXPECT_EQ(stored.voxels, decoded) << index;
    }
    EXPECT_TRUE(sculptor.take_stored_voxels().empty());  // taken
  }
}

// Trilinear density of g at p.
float sample(const DenseGrid<uint8_t>& g, glm::vec3 p) {
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
}

// Distance from `centre` along `dir` at which the density falls to 127.5.
float radial_height(const DenseGrid<uint8_t>& g, glm::vec3 centre, glm::vec3 dir, float from,
                    float to) {
  float r = from;
  while (r < to && sample(g, centre + r * dir) >= 127.5f)
    r += 0.25f;
  float lo = r - 0.25f, hi = r;
  for (int i = 0; i < 30; ++i) {
    const float m = 0.5f * (lo + hi);
    (sample(g, centre + m * dir) >= 127.5f ? lo : hi) = m;
  }
  return 0.5f * (lo + hi);
}

struct Swelling {
  float worst_step;  // largest change between profile samples 0.25 voxel apart
  float worst_rise;  // largest rise going from the crest outward (should be none)
  float crest_range;
  float crest_height;  // above the untouched sphere
};

// A stroke at `strength` along the equator of a radius-30 sphere, radius-10
// ball of `hardness`; the surface's profile across it and along its crest.
Swelling swell_sphere(float hardness, float strength) {
  constexpr int n = 96;
  Volume v = sphere_volume(n, 30.0f / n);
  const glm::vec3 c(0.5f * (n - 1));
  const float rs = 30.0f;
  Sculptor s(v);
  s.set_tool(make_sphere_tool(10.0f, hardness));
  std::vector<StrokeSample> path;
  for (float a = -1.0f; a <= 1.0001f; a += 2.0f / rs)  // every 2 voxels of arc
    path.push_back({c + rs * glm::vec3(std::cos(a), std::sin(a), 0.0f), glm::quat(1, 0, 0, 0)});
  (void)sweep_stroke(s, path, {SculptMode::kAdd, strength, false});
  const DenseGrid<uint8_t> g = v.to_dense();
  Swelling out{0.0f, 0.0f, 0.0f, 0.0f};
  auto height = [&](float theta, float phi) {
    const glm::vec3 dir(std::cos(theta) * std::cos(phi), std::sin(theta) * std::cos(phi),
                        std::sin(phi));
    return radial_height(g, c, dir, rs - 4.0f, rs + 6.0f);
  };
  // Across, from the crest to beyond the ball's reach (both sides), 0.25
  // voxel of arc apart.
  for (float side : {1.0f, -1.0f}) {
    float prev = height(0.0f, 0.0f);
    for (float arc = 0.25f; arc <= 14.0f; arc += 0.25f) {
      const float h = height(0.0f, side * arc / rs);
      out.worst_step = std::max(out.worst_step, std::abs(h - prev));
      out.worst_rise = std::max(out.worst_rise, h - prev);
      prev = h;
    }
  }
  float lo = 1e9f, hi = -1e9f;
  for (float arc = -12.0f; arc <= 12.0f; arc += 0.25f) {
    const float h = height(arc / rs, 0.0f);
    lo = std::min(lo, h);
    hi = std::max(hi, h);
  }
  out.crest_range = hi - lo;
  out.crest_height = height(0.0f, 0.0f) - height(0.0f, 0.6f);
  return out;
}

// Strength 0.15 swells the surface by 0.3 voxel. Measured (hardness 0 / 1):
// largest step 0.014 / 0.042, largest rise outward 0.003 (the untouched
// sphere's own noise) / 0.009, crest range 0.030 / 0.024. Stronger strokes
// keep the profile monotonic, but their crest varies more with the grid (0.047
// at strength 0.2, 0.12 at 0.3): the swollen surface then lies near the end of
// the material's 2-voxel density ramp, where its density is clamped at 0 and
// linear interpolation (this measure's, and marching cubes') misplaces it.
// That is the density model's limit, not the sweep's.
TEST(SweptStroke, PartialStrengthSoftStrokeSwellsWithoutATerrace) {
  const Swelling soft = swell_sphere(0.0f, 0.15f);
  EXPECT_GT(soft.crest_height, 0.25f);  // it did swell
  EXPECT_LE(soft.worst_step, 0.05f);
  EXPECT_LE(soft.worst_rise, 0.005f);  // monotonic from the crest outward
  EXPECT_LE(soft.crest_range, 0.05f);
  // The hard ball's rim raises its whole width by the same fraction and
  // leaves a ridge at its edge: what the profile test is there to catch.
  const Swelling hard = swell_sphere(1.0f, 0.15f);
  EXPECT_GT(hard.worst_rise, 0.005f);
  // At strength 0.2 the hard edge's step passes the 0.05 too; the
  // soft one stays smooth.
  EXPECT_GT(swell_sphere(1.0f, 0.2f).worst_step, 0.05f);
  EXPECT_LE(swell_sphere(0.0f, 0.2f).worst_step, 0.05f);
}

TEST(SweptStroke, OverlapsOfOneStrokeDoNotAccumulateUnlessAsked) {
  const glm::vec3 a(20.0f, 24.0f, 34.3f), b(80.0f, 24.0f, 34.3f);
  auto there = straight_path(a, b, 3.0f);
  auto back = straight_path(b, a, 3.0f);
  std::vector<StrokeSample> there_and_back = there;
  there_and_back.insert(there_and_back.end(), back.begin(), back.end());
  auto run = [&](const std::vector<StrokeSample>& path, bool accumulate) {
    Volume v = slab_volume(kSlab, kTop);
    Sculptor s(v);
    s.set_tool(make_sphere_tool(8.0f, 0.3f));
    (void)sweep_stroke(s, path, {SculptMode::kAdd, 0.4f, accumulate});
    return v.to_dense();
  };
  const DenseGrid<uint8_t> once = run(there, false);
  EXPECT_EQ(run(there_and_back, false).values(), once.values());
  // Accumulating, one pass is the same (consecutive segments' joints are
  // not applied twice), and the way back builds up.
  const DenseGrid<uint8_t> once_acc = run(there, true);
  int worst = 0;
  for (size_t i = 0; i < once.size(); ++i)
    worst = std::max(worst, std::abs(int(once[i]) - int(once_acc[i])));
  EXPECT_LE(worst, 2);
  const DenseGrid<uint8_t> twice_acc = run(there_and_back, true);
  int64_t more = 0, sum_once = 0, sum_twice = 0;
  for (size_t i = 0; i < once.size(); ++i) {
    more += twice_acc[i] > once_acc[i];
    sum_once += once_acc[i];
    sum_twice += twice_acc[i];
  }
  EXPECT_GT(more, 1000);
  EXPECT_GT(sum_twice, sum_once);
}

TEST(SweptStroke, UndoAndRedoAreBitExact) {
  Volume v = sphere_volume(96, 0.3f);
  const uint64_t h0 = v.content_hash();
  Sculptor s(v);
  s.set_tool(make_sphere_tool(6.0f, 0.5f));
  const auto path = straight_path({20.0f, 47.5f, 76.0f}, {75.0f, 50.0f, 70.0f}, 5.0f);
  const DabStats st = sweep_stroke(s, path, {SculptMode::kSubtract, 0.8f, false});
  EXPECT_GT(st.voxels_changed, 0);
  const uint64_t h1 = v.content_hash();
  EXPECT_NE(h1, h0);
  EXPECT_EQ(s.history().undo_depth(), 1u);
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(v.content_hash(), h0);
  ASSERT_TRUE(s.redo());
  EXPECT_EQ(v.content_hash(), h1);
}

TEST(SweptStroke, UnionAndDifferenceStay) {
  const auto path = straight_path({20.0f, 24.0f, 24.0f}, {90.0f, 24.0f, 24.0f}, 4.0f);
  auto run = [&](uint8_t fill, SculptMode mode) {
    Volume v(kSlab, fill);
    Sculptor s(v);
    s.set_tool(make_sphere_tool(8.0f));
    (void)sweep_stroke(s, path, {mode, 1.0f, false});
    return v.to_dense();
  };
  // On empty material union is add; on full, difference is subtract.
  const DenseGrid<uint8_t> u = run(0, SculptMode::kUnion);
  EXPECT_EQ(u.values(), run(0, SculptMode::kAdd).values());
  EXPECT_EQ(run(255, SculptMode::kDifference).values(), run(255, SculptMode::kSubtract).values());
  // And union keeps what is already fuller: a half-full block gets no dent.
  const DenseGrid<uint8_t> half = run(128, SculptMode::kUnion);
  for (size_t i = 0; i < half.size(); ++i)
    ASSERT_EQ(half[i], std::max<uint8_t>(128, u[i]));
}

// A tool's sweep (placements along each segment) counts the rotated voxels
// it asks its cache for, as dabs do: `--stats` reports them.
TEST(SweptStroke, AToolsSweepCountsItsRotatedVoxelsInTheCache) {
  const auto path = straight_path({20.0f, 24.0f, 24.0f}, {40.0f, 24.0f, 24.0f}, 4.0f);
  Volume v(kSlab, 0);
  Sculptor s(v);
  s.set_tool(make_cube_tool(8.0f));
  (void)sweep_stroke(s, path, {SculptMode::kAdd, 1.0f, false});
  const RotatedToolCacheStats stats = s.rotation_cache_stats();
  EXPECT_GT(stats.placements, 0);
  EXPECT_GT(stats.voxels_requested, 0);
  // Each requested voxel was reused or rotated (gaps between stretches are
  // rotated too).
  EXPECT_GE(stats.voxels_reused + stats.voxels_rotated, stats.voxels_requested);
}

TEST(SweptStroke, MirroredStrokeIsSymmetric) {
  Volume v = slab_volume(kSlab, kTop);
  Sculptor s(v);
  s.set_tool(make_sphere_tool(6.0f));
  s.set_mirror(MirrorPlane{1, 0.5f * (kSlab.y - 1)});
  const auto path = straight_path({20.0f, 10.3f, 32.0f}, {90.0f, 17.0f, 33.0f}, 6.0f);
  (void)sweep_stroke(s, path, {SculptMode::kSubtract, 1.0f, false});
  const DenseGrid<uint8_t> g = v.to_dense();
  int64_t cut = 0;
  for (int z = 0; z < kSlab.z; ++z)
    for (int y = 0; y < kSlab.y; ++y)
      for (int x = 0; x < kSlab.x; ++x) {
        ASSERT_EQ(g.at(x, y, z), g.at(x, kSlab.y - 1 - y, z)) << x << " " << y << " " << z;
        cut += g.at(x, y, z) < density_from_distance(static_cast<float>(z) - kTop);
      }
  EXPECT_GT(cut, 1000);
}

// Mirrored across x, a segment's two sweeps cross the same rows of voxels,
// and near the plane the same brick: each row must take what both add. (The
// path runs just above the plane: its mirror image is the second sweep and
// lies lower along the rows. A row's grown stretch ended at the second
// sweep's, and the material the first added beyond it was lost: 245 against
// 255 at the mirrored voxel.)
TEST(SweptStroke, StrokeMirroredAcrossItsRowsIsSymmetric) {
  Volume v = slab_volume(kSlab, kTop);
  Sculptor s(v);
  s.set_tool(make_sphere_tool(6.0f));
  s.set_mirror(MirrorPlane{0, 0.5f * (kSlab.x - 1)});
  const auto path = straight_path({60.3f, 6.0f, 32.0f}, {61.0f, 42.0f, 33.0f}, 6.0f);
  for (const SculptMode mode : {SculptMode::kSubtract, SculptMode::kAdd}) {
    (void)sweep_stroke(s, path, {mode, 1.0f, false});
    const DenseGrid<uint8_t> g = v.to_dense();
    for (int z = 0; z < kSlab.z; ++z)
      for (int y = 0; y < kSlab.y; ++y)
        for (int x = 0; x < kSlab.x; ++x)
          ASSERT_EQ(g.at(x, y, z), g.at(kSlab.x - 1 - x, y, z)) << x << " " << y << " " << z;
  }
}

// A ball held as a plain grid has no analytic sweep: it is placed along the
// segment. Its groove is still flat and where the ball went.
TEST(SweptStroke, AnyToolIsSweptWithoutScallops) {
  Volume v = slab_volume(kSlab, kTop);
  Sculptor s(v);
  s.set_tool(tool_from_grid(make_sphere_tool(8.0f).density));
  const auto path = straight_path({10.0f, kPathY, kPathZ}, {100.0f, kPathY, kPathZ}, 4.0f);
  (void)sweep_stroke(s, path, {SculptMode::kSubtract, 1.0f, false});
  const DenseGrid<uint8_t> g = v.to_dense();
  float lo = 1e9f, hi = -1e9f;
  for (int x = 30; x <= 80; ++x) {
    const float f = floor_height(g, x, static_cast<int>(kPathY), static_cast<int>(kPathZ));
    lo = std::min(lo, f);
    hi = std::max(hi, f);
    EXPECT_NEAR(f, kPathZ - 8.0f, 0.1f) << "x " << x;
  }
  EXPECT_LE(hi - lo, 0.03f);
}

// A cube turned in place by 45 degrees about z in one segment cuts what it
// swept through: the corners of the 22.5-degree cube, which neither end's
// cube reaches.
TEST(SweptStroke, OrientationIsInterpolatedAlongTheSweep) {
  Volume v(glm::ivec3(64), 255);
  Sculptor s(v);
  s.set_tool(make_cube_tool(20.0f));
  const glm::vec3 c(32.0f);
  const glm::quat turn = glm::angleAxis(glm::radians(45.0f), glm::vec3(0, 0, 1));
  const std::vector<StrokeSample> path = {{c, glm::quat(1, 0, 0, 0)}, {c, turn}};
  (void)sweep_stroke(s, path, {SculptMode::kSubtract, 1.0f, false});
  const DenseGrid<uint8_t> g = v.to_dense();
  // The corner direction of the 22.5-degree cube, just inside it (corner at
  // 10 sqrt 2 = 14.1 from the centre); the end cubes reach 10 and 14.1 along
  // 0 and 45 degrees, about 10.8 along 22.5 + 45 = 67.5 mod 90.
  const float a = glm::radians(45.0f + 22.5f);
  const glm::vec3 p = c + 12.0f * glm::vec3(std::cos(a), std::sin(a), 0.0f);
  EXPECT_EQ(g.at(int(std::lround(p.x)), int(std::lround(p.y)), 32), 0);
  // Beyond every turn's corner the material is untouched.
  const glm::vec3 q = c + 16.0f * glm::vec3(std::cos(a), std::sin(a), 0.0f);
  EXPECT_EQ(g.at(int(std::lround(q.x)), int(std::lround(q.y)), 32), 255);
}

// Samples added at once (a stamp's path, or a device report's several dabs)
// give the material that adding them one by one gives, byte for byte, and
// store each brick once: hard, soft and grid tools, mirrored, at partial
// strength, over more samples than one batch holds.
TEST(SweptStroke, SamplesAtOnceEqualSamplesOneByOne) {
  std::vector<StrokeSample> path;
  // More samples than one batch holds (256 segments).
  for (int k = 0; k < 300; ++k) {
    const float a = 0.07f * static_cast<float>(k);
    path.push_back({glm::vec3(56.0f + 30.0f * std::cos(a), 24.0f + 14.0f * std::sin(a),
                              31.0f + 2.0f * std::sin(3.0f * a)),
                    glm::angleAxis(a, glm::normalize(glm::vec3(1.0f, 2.0f, 3.0f)))});
  }
  struct Case {
    Tool tool;
    bool mirror;
    SculptMode mode;
    float strength;
  };
  const std::vector<Case> cases = {
      {make_sphere_tool(7.0f), false, SculptMode::kSubtract, 1.0f},
      {make_sphere_tool(7.0f, 0.4f), true, SculptMode::kAdd, 0.6f},
      {make_cube_tool(9.0f), false, SculptMode::kSubtract, 0.8f},
      {make_sphere_tool(5.0f), true, SculptMode::kUnion, 1.0f},
  };
  for (const Case& c : cases) {
    auto run = [&](bool at_once, DabStats& stats) {
      Volume v = slab_volume(kSlab, kTop);
      Sculptor s(v);
      s.set_tool(c.tool);
      if (c.mirror) s.set_mirror(MirrorPlane{0, 0.5f * (kSlab.x - 1)});
      SweptStroke stroke(s, {c.mode, c.strength, false});
      if (at_once) {
        stats += stroke.add(path);
      } else {
        for (const StrokeSample& p : path)
          stats += stroke.add(p);
      }
      stroke.finish();
      return v.content_hash();
    };
    DabStats one_by_one, at_once;
    EXPECT_EQ(run(false, one_by_one), run(true, at_once));
    EXPECT_GT(one_by_one.voxels_changed, 1000);
    EXPECT_LT(at_once.bricks_changed, one_by_one.bricks_changed);
  }
}

// A big ball's segments reach dozens of bricks, combined on every core: the
// same volume, brick for brick, as on one.
TEST(SweptStroke, ABigBallOnEveryCoreEqualsOneCore) {
  auto run = [](int threads) {
    set_default_threads(threads);
    Volume v = sphere_volume(160, 0.3f);
    Sculptor s(v);
    s.set_tool(make_sphere_tool(40.0f, 0.6f));
    const auto path = straight_path({30.0f, 80.0f, 120.0f}, {130.0f, 75.0f, 110.0f}, 9.0f);
    const DabStats st = sweep_stroke(s, path, {SculptMode::kSubtract, 0.9f, false});
    set_default_threads(0);
    // Bricks combined (the path is one batch): enough for every core.
    EXPECT_GE(st.bricks_decoded + st.bricks_reused, 16);
    return v.content_hash();
  };
  EXPECT_EQ(run(1), run(4));
}

// A thread's kept buffers (keep_stroke_buffers(), which the sculpting thread
// calls when it starts) serve its strokes and come back when they end; what
// an earlier stroke left in them changes nothing: the same volume as a
// stroke on a thread that allocates every buffer anew.
TEST(SweptStroke, KeptBuffersServeStrokesAndComeBackUnread) {
  auto carve = [] {
    Volume v = sphere_volume(160, 0.3f);
    Sculptor s(v);
    s.set_tool(make_sphere_tool(30.0f, 0.8f));
    const auto path = straight_path({40.0f, 80.0f, 110.0f}, {120.0f, 70.0f, 100.0f}, 7.0f);
    const DabStats st = sweep_stroke(s, path, {SculptMode::kSubtract, 1.0f, false});
    return std::make_pair(v.content_hash(), st.bricks_decoded);
  };
  uint64_t fresh = 0, kept = 0;
  std::thread([&] { fresh = carve().first; }).join();
  std::thread([&] {
    keep_stroke_buffers(32, 40);
    EXPECT_EQ(stroke_buffers_kept(), 120u);
    // Served from the pool (none discarded, none allocated) and given back.
    const auto [first_hash, decoded] = carve();
    EXPECT_EQ(first_hash, fresh);
    EXPECT_GT(decoded, 4);
    EXPECT_LT(decoded, 40);
    EXPECT_EQ(stroke_buffers_kept(), 120u);
    // Another stroke, leaving its voxels in the buffers, then the carve again.
    Volume other = sphere_volume(160, 0.45f);
    Sculptor s(other);
    s.set_tool(make_sphere_tool(50.0f));
    (void)sweep_stroke(s, straight_path({20.0f, 20.0f, 20.0f}, {140.0f, 140.0f, 140.0f}, 9.0f),
                       {SculptMode::kAdd, 1.0f, false});
    kept = carve().first;
  }).join();
  EXPECT_EQ(kept, fresh);
}

// A turning ring's segments rotate a placement every half voxel, mirrored;
// its bricks, on every core, fill rows of the same placements at once
// (bricks side by side in x share rows): the same volume, and the same
// rotated voxels asked for, as on one core.
TEST(SweptStroke, ATurningToolOnEveryCoreEqualsOneCore) {
  auto run = [](int threads, RotatedToolCacheStats* counts) {
    set_default_threads(threads);
    Volume v = sphere_volume(160, 0.3f);
    Sculptor s(v);
    s.set_tool(make_ring_tool(12.0f, 5.0f));
    s.set_mirror(MirrorPlane{0, 80.0f});
    std::vector<StrokeSample> path;
    for (int i = 0; i <= 8; ++i) {
      const float fi = static_cast<float>(i);
      const float a = 0.15f * fi;
      path.push_back({glm::vec3(56.0f + 3.0f * fi, 40.0f + 8.0f * fi, 80.0f + 20.0f * std::sin(a)),
                      glm::angleAxis(a, glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f)))});
    }
    const DabStats st = sweep_stroke(s, path, {SculptMode::kSubtract, 1.0f, false});
    set_default_threads(0);
    EXPECT_GE(st.bricks_decoded + st.bricks_reused, 16);  // enough for every core
    EXPECT_GT(st.voxels_changed, 10000);
    *counts = s.rotation_cache_stats();
    return v.content_hash();
  };
  RotatedToolCacheStats one, every;
  EXPECT_EQ(run(1, &one), run(4, &every));
  EXPECT_EQ(one.placements, every.placements);
  EXPECT_EQ(one.voxels_requested, every.voxels_requested);
  EXPECT_GT(one.voxels_rotated, 0);
}

// On empty material, adding at full strength leaves each voxel exactly the
// ball's filling: tool_density() of its distance to the nearest segment,
// computed here voxel by voxel for paths in every direction.
TEST(SweptStroke, ABallsSweepIsItsDistanceToThePath) {
  uint32_t seed = 7;
  auto rnd = [&](float lo, float hi) {
    seed = seed * 1664525u + 1013904223u;
    return lo + (hi - lo) * static_cast<float>(seed >> 8) / 16777216.0f;
  };
  for (float hardness : {1.0f, 0.4f}) {
    const float r = 6.5f;
    std::vector<StrokeSample> path;
    for (int i = 0; i < 7; ++i)
      path.push_back({{rnd(12, 52), rnd(12, 52), rnd(12, 52)}, glm::quat(1, 0, 0, 0)});
    path.push_back(path.back());  // a segment of length 0
    path.push_back({path.back().position_vox + glm::vec3(9.0f, 0.0f, 0.0f), {}});  // along x
    Volume v(glm::ivec3(64), uint8_t{0});
    Sculptor s(v);
    s.set_tool(make_sphere_tool(r, hardness));
    (void)sweep_stroke(s, path, {SculptMode::kAdd, 1.0f, false});
    const DenseGrid<uint8_t> g = v.to_dense();
    int64_t off = 0;
    int worst = 0;
    for (int z = 0; z < 64; ++z)
      for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
          const glm::vec3 p(x, y, z);
          float d = glm::length(p - path[0].position_vox);
          for (size_t i = 1; i < path.size(); ++i) {
            const glm::vec3 a = path[i - 1].position_vox, ab = path[i].position_vox - a;
            const float ab2 = glm::dot(ab, ab);
            const float t = ab2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / ab2, 0.0f, 1.0f) : 0.0f;
            d = std::min(d, glm::length(p - a - t * ab));
          }
          const int want = tool_density(d - r, r, hardness);
          const int diff = std::abs(want - int(g.at(x, y, z)));
          worst = std::max(worst, diff);
          off += diff != 0;
        }
    // Float rounding of the distance may move a voxel by one unit.
    EXPECT_LE(worst, 1) << "hardness " << hardness;
    EXPECT_LT(off, 200) << "hardness " << hardness;
  }
}

}  // namespace
}  // namespace sculpt::core
