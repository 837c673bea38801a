#include "sculpt/core/sculpt/sculptor.h"

#include <gtest/gtest.h>

#include <cstdlib>

#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core {
namespace {

// A volume of noise in [lo, hi], so a lost or doubled change shows anywhere.
Volume noise_volume(glm::ivec3 dims, int lo, int hi) {
  DenseGrid<uint8_t> g(dims);
  uint32_t s = 99;
  for (uint8_t& v : g.values()) {
    s = s * 1664525u + 1013904223u;
    v = static_cast<uint8_t>(lo + (s >> 16) % (hi - lo + 1));
  }
  return Volume::from_dense(g);
}

const glm::quat kTurn = glm::normalize(glm::quat(0.8f, 0.3f, -0.4f, 0.2f));

TEST(Sculptor, AddThenSubtractRestoresWhereNothingClamped) {
  Volume v = noise_volume({70, 60, 50}, 0, 127);
  const uint64_t before = v.content_hash();
  Sculptor s(v);
  s.set_tool(make_cone_tool(9.0f, 14.0f));
  // At strength 0.5 the filling adds at most 128: 127 + 128 never clamps.
  Dab d{{33.3f, 30.6f, 20.1f}, kTurn, SculptMode::kAdd, 0.5f};
  const DabStats add = s.dab(d);
  EXPECT_GT(add.voxels_changed, 0);
  EXPECT_NE(v.content_hash(), before);
  d.mode = SculptMode::kSubtract;
  (void)s.dab(d);
  EXPECT_EQ(v.content_hash(), before);
}

TEST(Sculptor, AddThenSubtractDiffersOnlyWhereAddClamped) {
  Volume v(glm::ivec3(64), 200);
  Sculptor s(v);
  s.set_tool(make_sphere_tool(8.0f));
  Dab d{{31.5f, 30.2f, 33.7f}, kTurn, SculptMode::kAdd, 1.0f};
  (void)s.dab(d);
  const DenseGrid<uint8_t> added = v.to_dense();
  d.mode = SculptMode::kSubtract;
  (void)s.dab(d);
  const DenseGrid<uint8_t> after = v.to_dense();
  int64_t clamped = 0;
  for (size_t i = 0; i < after.size(); ++i) {
    if (added[i] == 255) {
      ++clamped;
      EXPECT_LE(after[i], 200);
    } else {
      ASSERT_EQ(after[i], 200) << "voxel " << i;
    }
  }
  EXPECT_GT(clamped, 0);
}

TEST(Sculptor, UndoAndRedoAreBitExactPerStroke) {
  Volume v = sphere_volume(96, 0.3f);
  const uint64_t h0 = v.content_hash();
  Sculptor s(v);
  s.set_tool(make_cube_tool(10.0f));
  s.begin_stroke();
  for (int i = 0; i < 6; ++i) {
    (void)s.dab(
        {{30.0f + 3.1f * static_cast<float>(i), 40.0f, 48.5f}, kTurn, SculptMode::kSubtract, 1.0f});
  }
  s.end_stroke();
  const uint64_t h1 = v.content_hash();
  s.set_tool(make_ring_tool(7.0f, 2.5f));
  s.begin_stroke();
  (void)s.dab({{60.2f, 50.0f, 40.0f}, glm::quat(1, 0, 0, 0), SculptMode::kAdd, 0.7f});
  (void)s.dab({{61.2f, 52.0f, 40.0f}, kTurn, SculptMode::kSmooth, 1.0f});
  (void)s.dab({{55.0f, 45.0f, 44.0f}, kTurn, SculptMode::kDifference, 1.0f});
  (void)s.dab({{50.0f, 60.0f, 30.0f}, kTurn, SculptMode::kUnion, 0.9f});
  s.end_stroke();
  const uint64_t h2 = v.content_hash();
  ASSERT_NE(h1, h0);
  ASSERT_NE(h2, h1);
  EXPECT_EQ(s.history().undo_depth(), 2u);
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(v.content_hash(), h1);
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(v.content_hash(), h0);
  EXPECT_FALSE(s.undo());
  ASSERT_TRUE(s.redo());
  EXPECT_EQ(v.content_hash(), h1);
  ASSERT_TRUE(s.redo());
  EXPECT_EQ(v.content_hash(), h2);
  EXPECT_FALSE(s.redo());
  // A new stroke after an undo clears the redo list.
  ASSERT_TRUE(s.undo());
  (void)s.dab({{20.0f, 20.0f, 20.0f}, kTurn, SculptMode::kAdd, 1.0f});
  EXPECT_FALSE(s.redo());
}

TEST(Sculptor, UndoMemoryCapForgetsOldestStrokes) {
  Volume v = sphere_volume(96, 0.3f);
  SculptorOptions o;
  o.undo_max_bytes = 200 * 1024;  // a few detailed bricks
  Sculptor s(v, o);
  s.set_tool(make_sphere_tool(6.0f));
  for (int i = 0; i < 8; ++i)
    (void)s.dab(
        {{20.0f + 8.0f * static_cast<float>(i), 48.0f, 19.0f}, kTurn, SculptMode::kSubtract, 1.0f});
  EXPECT_LE(s.history().memory_bytes(), o.undo_max_bytes);
  EXPECT_GT(s.history().dropped_strokes(), 0);
  EXPECT_LT(s.history().undo_depth(), 8u);
}

TEST(Sculptor, MirrorIsSymmetricAndUndoneWithItsStroke) {
  Volume v(glm::ivec3(80, 48, 48), 0);
  Sculptor s(v);
  s.set_tool(make_cone_tool(6.0f, 11.0f));
  s.set_mirror(MirrorPlane{0, 39.5f});
  s.begin_stroke();
  (void)s.dab({{20.3f, 22.6f, 24.2f}, kTurn, SculptMode::kAdd, 1.0f});
  (void)s.dab(
      {{25.3f, 21.6f, 26.2f}, glm::angleAxis(0.7f, glm::vec3(0, 1, 0)), SculptMode::kAdd, 1.0f});
  s.end_stroke();
  const DenseGrid<uint8_t> g = v.to_dense();
  int64_t mass = 0;
  int worst = 0;
  for (int z = 0; z < 48; ++z)
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 80; ++x) {
        mass += g.at(x, y, z);
        worst = std::max(worst, std::abs(g.at(x, y, z) - g.at(79 - x, y, z)));
      }
  EXPECT_GT(mass, 0);
  // The mirrored samples sit at mirrored fixed-point positions; the 8-bit
  // trilinear weights round the two sides differently by a step or two.
  EXPECT_LE(worst, 2);
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(v.content_hash(), Volume(glm::ivec3(80, 48, 48), 0).content_hash());
}

TEST(Sculptor, DabVisitsOnlyBricksItCanChange) {
  Volume v(glm::ivec3(128), 0);
  Sculptor s(v);
  s.set_tool(make_sphere_tool(10.0f));
  // Subtracting from empty space: nothing is decoded, nothing rotated.
  const DabStats empty = s.dab({{64.0f, 64.0f, 64.0f}, kTurn, SculptMode::kSubtract, 1.0f});
  EXPECT_GT(empty.bricks_overlapped, 0);
  EXPECT_EQ(empty.bricks_decoded, 0);
  EXPECT_EQ(s.cache().stats().voxels_rotated, 0);
  EXPECT_TRUE(v.take_dirty_bricks().empty());
  // Adding at a brick corner touches the 8 bricks around it, and marks
  // exactly the changed ones dirty.
  const DabStats add = s.dab({{64.0f, 64.0f, 64.0f}, kTurn, SculptMode::kAdd, 1.0f});
  EXPECT_EQ(add.bricks_changed, 8);
  EXPECT_EQ(v.take_dirty_bricks().size(), 8u);
  // The same orientation moved by whole voxels reuses the rotated voxels.
  const int64_t rotated = s.cache().stats().voxels_rotated;
  (void)s.dab({{65.0f, 64.0f, 63.0f}, kTurn, SculptMode::kAdd, 1.0f});
  EXPECT_EQ(s.cache().stats().placement_hits, 2);
  EXPECT_LT(s.cache().stats().voxels_rotated - rotated, rotated / 4);
  // Outside the volume: nothing at all.
  const DabStats outside = s.dab({{-100.0f, 5.0f, 5.0f}, kTurn, SculptMode::kAdd, 1.0f});
  EXPECT_EQ(outside.bricks_overlapped, 0);
}

TEST(Sculptor, FillingMatchesTheRotatedTool) {
  Volume v(glm::ivec3(64), 0);
  Sculptor s(v);
  const Tool tool = make_cone_tool(7.0f, 12.0f);
  s.set_tool(tool);
  const glm::vec3 pos(30.0f, 31.0f, 29.0f);
  (void)s.dab({pos, kTurn, SculptMode::kUnion, 1.0f});
  // The union into empty material is the rotated tool itself.
  const RotatedTool rt = rotate_tool(PreparedTool(tool), glm::mat3_cast(kTurn), pos,
                                     RotationMethod::kIncremental, Sampling::kTrilinear);
  int64_t total = 0;
  int worst = 0;
  const glm::ivec3 d = rt.density.dims();
  for (int z = 0; z < d.z; ++z)
    for (int y = 0; y < d.y; ++y)
      for (int x = 0; x < d.x; ++x) {
        const int want = rt.density.at(x, y, z);
        total += want;
        worst = std::max(worst, std::abs(v.voxel(glm::ivec3(x, y, z) + rt.origin) - want));
      }
  EXPECT_GT(total, 0);
  // The cache quantises the orientation to 2^-20: a rounding step at most.
  EXPECT_LE(worst, 2);
}

TEST(Sculptor, KeptDecodedBricksGiveTheSameResultAndSeeOtherWriters) {
  Volume a = sphere_volume(96, 0.3f);
  Volume b = a;
  Sculptor kept(a);
  kept.set_tool(make_sphere_tool(7.0f));
  // On the surface, at the corner of 8 bricks.
  const Dab d1{{64.0f, 64.0f, 64.0f}, kTurn, SculptMode::kSubtract, 1.0f};
  const Dab d2{{62.5f, 65.0f, 63.0f}, kTurn, SculptMode::kAdd, 0.6f};
  (void)kept.dab(d1);
  // Another writer changes a brick the kept voxels cover.
  a.write(glm::ivec3(56, 56, 56), DenseGrid<uint8_t>(glm::ivec3(4), 77));
  const DabStats second = kept.dab(d2);
  EXPECT_EQ(second.bricks_reused, 7);
  EXPECT_EQ(second.bricks_decoded, 1);
  // The same edits, each through a fresh sculptor (no kept bricks).
  for (const Dab& d : {d1}) {
    Sculptor fresh(b);
    fresh.set_tool(make_sphere_tool(7.0f));
    (void)fresh.dab(d);
  }
  b.write(glm::ivec3(56, 56, 56), DenseGrid<uint8_t>(glm::ivec3(4), 77));
  {
    Sculptor fresh(b);
    fresh.set_tool(make_sphere_tool(7.0f));
    (void)fresh.dab(d2);
  }
  EXPECT_EQ(a.content_hash(), b.content_hash());
}

// A dab over many bricks is decoded and combined on every core, a small one
// on the calling thread with its decoded bricks kept: both make the same
// voxels and undo the same.
TEST(Sculptor, ABigDabOnEveryCoreEqualsItsBricksOneByOne) {
  const DenseGrid<uint8_t> noise = [] {
    DenseGrid<uint8_t> g(glm::ivec3(96));
    uint32_t s = 7;
    for (uint8_t& v : g.values()) {
      s = s * 1664525u + 1013904223u;
      v = static_cast<uint8_t>(40 + (s >> 16) % 160);
    }
    return g;
  }();
  // 8-voxel bricks: the 24-voxel ball touches some 300 (parallel); 64-voxel
  // bricks: at most 8 (one by one). The content hash is brick-size blind.
  VolumeOptions small_bricks, big_bricks;
  small_bricks.brick_edge = 8;
  small_bricks.levels = 3;
  big_bricks.brick_edge = 64;
  for (SculptMode mode : {SculptMode::kAdd, SculptMode::kSubtract, SculptMode::kSmooth}) {
    Volume many = Volume::from_dense(noise, small_bricks);
    Volume few = Volume::from_dense(noise, big_bricks);
    const uint64_t original = many.content_hash();
    Sculptor a(many), b(few);
    a.set_tool(make_sphere_tool(24.0f));
    b.set_tool(make_sphere_tool(24.0f));
    const Dab dab{{47.3f, 50.6f, 44.1f}, kTurn, mode, 0.7f};
    const DabStats sa = a.dab(dab);
    const DabStats sb = b.dab(dab);
    ASSERT_GE(sa.bricks_changed, 100) << sculpt_mode_name(mode);
    ASSERT_LE(sb.bricks_overlapped, 8) << sculpt_mode_name(mode);
    EXPECT_EQ(many.content_hash(), few.content_hash()) << sculpt_mode_name(mode);
    EXPECT_NE(many.content_hash(), original) << sculpt_mode_name(mode);
    EXPECT_EQ(sa.voxels_changed, sb.voxels_changed) << sculpt_mode_name(mode);
    EXPECT_GT(a.cache().stats().voxels_rotated, 0) << sculpt_mode_name(mode);
    ASSERT_TRUE(a.undo());
    EXPECT_EQ(many.content_hash(), original) << sculpt_mode_name(mode);
  }
}

TEST(Sculptor, RotationCacheCountsOutliveToolChanges) {
  Volume v({48, 48, 48}, 0);
  Sculptor s(v);
  s.set_tool(make_sphere_tool(5.0f));
  const Dab d{{20.25f, 24.0f, 24.0f}, kTurn, SculptMode::kAdd, 1.0f};
  (void)s.dab(d);
  (void)s.dab(d);  // the same placement: a hit
  EXPECT_EQ(s.rotation_cache_stats().placements, 2);
  EXPECT_EQ(s.rotation_cache_stats().placement_hits, 1);
  s.set_tool(make_cube_tool(6.0f));  // a new cache; the counts stay
  s.set_mirror(MirrorPlane{0, 24.0f});
  (void)s.dab(d);
  const RotatedToolCacheStats all = s.rotation_cache_stats();
  EXPECT_EQ(all.placements, 4);  // the cube's dab and its mirror image
  EXPECT_EQ(all.placement_hits, 1);
  EXPECT_DOUBLE_EQ(all.placement_hit_rate(), 0.25);
  EXPECT_EQ(all.entries, 2u);  // held now: the cube's and its mirror's
  EXPECT_EQ(s.cache().stats().placements, 1);
}

TEST(Sculptor, ModeNamesRoundTrip) {
  for (const char* n : {"add", "subtract", "union", "difference", "smooth"}) {
    const auto m = parse_sculpt_mode(n);
    ASSERT_TRUE(m.has_value()) << n;
    EXPECT_STREQ(sculpt_mode_name(*m), n);
  }
  EXPECT_FALSE(parse_sculpt_mode("carve").has_value());
}

}  // namespace
}  // namespace sculpt::core
