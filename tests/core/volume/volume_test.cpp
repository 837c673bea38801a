#include "sculpt/core/volume/volume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <thread>

#include "sculpt/core/shapes/analytic_shapes.h"
#include "sculpt/core/wavelet/haar_1d.h"

namespace sculpt::core {
namespace {

DenseGrid<uint8_t> random_grid(glm::ivec3 dims, uint32_t seed) {
  std::mt19937 rng(seed);
  DenseGrid<uint8_t> g(dims);
  for (uint8_t& v : g.values())
    v = static_cast<uint8_t>(rng());
  return g;
}

VolumeOptions small_bricks(int edge, int levels) {
  VolumeOptions o;
  o.brick_edge = edge;
  o.levels = levels;
  return o;
}

// Level k computed without the volume: pad level 0 by repeating the last
// voxel to a multiple of 2^k (what the far bricks' padding amounts to), then
// take nested S-transform floor averages of 2x2x2 blocks.
DenseGrid<uint8_t> reference_level(const DenseGrid<uint8_t>& g, int level) {
  const int s = 1 << level;
  const glm::ivec3 d = g.dims();
  DenseGrid<uint8_t> cur(((d + s - 1) / s) * s);
  for (int z = 0; z < cur.dims().z; ++z)
    for (int y = 0; y < cur.dims().y; ++y)
      for (int x = 0; x < cur.dims().x; ++x)
        cur.at(x, y, z) = g.at(std::min(x, d.x - 1), std::min(y, d.y - 1), std::min(z, d.z - 1));
  auto lo = [](int a, int b) { return haar::lift_forward(a, b).low; };
  for (int l = 0; l < level; ++l) {
    DenseGrid<uint8_t> next(cur.dims() / 2);
    auto v = [&](int x, int y, int z) { return int{cur.at(x, y, z)}; };
    for (int z = 0; z < next.dims().z; ++z)
      for (int y = 0; y < next.dims().y; ++y)
        for (int x = 0; x < next.dims().x; ++x) {
          const int X = 2 * x, Y = 2 * y, Z = 2 * z;
          const int z0 = lo(lo(v(X, Y, Z), v(X + 1, Y, Z)), lo(v(X, Y + 1, Z), v(X + 1, Y + 1, Z)));
          const int z1 = lo(lo(v(X, Y, Z + 1), v(X + 1, Y, Z + 1)),
                            lo(v(X, Y + 1, Z + 1), v(X + 1, Y + 1, Z + 1)));
          next.at(x, y, z) = static_cast<uint8_t>(lo(z0, z1));
        }
    cur = std::move(next);
  }
  return cur;
}

TEST(Volume, RoundTripIsBitExactForNonPowerOfTwoSizes) {
  for (glm::ivec3 dims : {glm::ivec3(1, 1, 1), glm::ivec3(45, 70, 33), glm::ivec3(16, 17, 15),
                          glm::ivec3(100, 3, 9)}) {
    const DenseGrid<uint8_t> g = random_grid(dims, static_cast<uint32_t>(dims.x));
    const Volume v = Volume::from_dense(g, small_bricks(16, 4));
    EXPECT_EQ(v.to_dense(0), g) << dims.x << "x" << dims.y << "x" << dims.z;
  }
}

TEST(Volume, LevelsOfTheBrickedVolumeEqualTheWholeVolumeTransform) {
  // Haar supports do not overlap, so bricking must not change any level,
  // including at the padded far faces.
  const DenseGrid<uint8_t> g = random_grid({45, 70, 33}, 9);
  const Volume v = Volume::from_dense(g, small_bricks(16, 4));
  for (int level = 0; level <= 4; ++level) {
    const DenseGrid<uint8_t> got = v.to_dense(level);
    EXPECT_EQ(got.dims(), v.level_dims(level));
    EXPECT_EQ(got, reference_level(g, level)) << "level " << level;
  }
}

TEST(Volume, BrickEdgeDoesNotChangeContentOrHash) {
  const DenseGrid<uint8_t> g = random_grid({40, 33, 20}, 4);
  const Volume a = Volume::from_dense(g, small_bricks(8, 3));
  const Volume b = Volume::from_dense(g, small_bricks(32, 3));
  EXPECT_EQ(a.to_dense(2), b.to_dense(2));
  EXPECT_EQ(a.content_hash(), b.content_hash());
  DenseGrid<uint8_t> changed = g;
  changed.at(39, 32, 19) ^= 1;
  EXPECT_NE(Volume::from_dense(changed, small_bricks(8, 3)).content_hash(), a.content_hash());
}

TEST(Volume, VoxelAndRegionReadsMatchTheDenseGrid) {
  const DenseGrid<uint8_t> g = random_grid({50, 41, 37}, 2);
  const Volume v = Volume::from_dense(g, small_bricks(16, 4));
  for (int z = 0; z < 37; z += 4)
    for (int y = 0; y < 41; y += 3)
      for (int x = 0; x < 50; ++x)
        ASSERT_EQ(v.voxel({x, y, z}), g.at(x, y, z));
  EXPECT_EQ(v.voxel({-1, 0, 0}), 0);
  EXPECT_EQ(v.voxel({50, 0, 0}), 0);

  // A region straddling brick edges and the volume's far faces.
  const Box region{{14, 30, 10}, {55, 41, 40}};
  const DenseGrid<uint8_t> r = v.read(region);
  for (int z = region.lo.z; z < region.hi.z; ++z)
    for (int y = region.lo.y; y < region.hi.y; ++y)
      for (int x = region.lo.x; x < region.hi.x; ++x) {
        const uint8_t expected = g.in_bounds(x, y, z) ? g.at(x, y, z) : 0;
        ASSERT_EQ(r.at(x - region.lo.x, y - region.lo.y, z - region.lo.z), expected);
      }
  // The same region at level 2 is a window of the whole level.
  const DenseGrid<uint8_t> whole = v.to_dense(2);
  const Box coarse{{3, 5, 2}, {13, 11, 10}};
  const DenseGrid<uint8_t> window = v.read(coarse, 2);
  for (int z = coarse.lo.z; z < coarse.hi.z; ++z)
    for (int y = coarse.lo.y; y < coarse.hi.y; ++y)
      for (int x = coarse.lo.x; x < coarse.hi.x; ++x)
        ASSERT_EQ(window.at(x - 3, y - 5, z - 2), whole.in_bounds(x, y, z) ? whole.at(x, y, z) : 0);
}

TEST(Volume, RecentlyStoredBricksReadBackAsTheirCoefficientsDecode) {
  // Bricks just stored are copied from their decoded voxels instead of being
  // decoded again; the copy must be exactly what decoding gives, for whole
  // and partial re-encodes and for border bricks (padded), and a brick
  // pushed out of the recent ones decodes as before.
  Volume volume =
      Volume::from_dense(sphere_density(100, 0.3f), VolumeOptions{.brick_edge = 16, .levels = 4});
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> at(0, 90), size(1, 12), value(0, 255);
  for (int round = 0; round < 40; ++round) {
    const glm::ivec3 lo{at(rng), at(rng), at(rng)};
    DenseGrid<uint8_t> patch(glm::ivec3(size(rng), size(rng), size(rng)), 0);
    for (uint8_t& v : patch.values())
      v = uint8_t(value(rng));
    volume.write(lo, patch);
    std::vector<uint8_t> copied(16 * 16 * 16), decoded(copied.size());
    for (int64_t i = 0; i < volume.brick_count(); ++i) {
      const glm::ivec3 b{int(i % 7), int(i / 7 % 7), int(i / 49)};
      volume.decode_brick(b, copied);
      volume.brick(b).extract_level(0, decoded);
      ASSERT_EQ(copied, decoded) << "round " << round << " brick " << i;
    }
  }
}

TEST(Volume, AReplacedBrickReadsAsTheOriginalsAndMovesItsVersion) {
  // A mirror (the station's mesher) follows the original brick by brick.
  const VolumeOptions options{.brick_edge = 16, .levels = 4};
  Volume original = Volume::from_dense(sphere_density(40), options);
  Volume mirror = original;
  DenseGrid<uint8_t> patch(glm::ivec3(6), 90);
  original.write({14, 14, 14}, patch);  // bricks (0..1)^3, now among the recent ones
  std::vector<uint8_t> stale(16 * 16 * 16);
  mirror.decode_brick({1, 1, 1}, stale);
  for (glm::ivec3 b : original.take_dirty_bricks()) {
    const uint64_t before = mirror.brick_version(b);
    mirror.replace_brick(b, original.brick(b));
    EXPECT_GT(mirror.brick_version(b), before);
  }
  EXPECT_EQ(mirror.content_hash(), original.content_hash());
  std::vector<uint8_t> want(stale.size()), got(stale.size());
  original.decode_brick({1, 1, 1}, want);
  mirror.decode_brick({1, 1, 1}, got);
  EXPECT_EQ(got, want);
  EXPECT_NE(got, stale);
  EXPECT_TRUE(mirror.take_dirty_bricks().empty());  // a mirror has nothing to re-mesh for us
}

TEST(Volume, BricksHoldTheSameVoxelsExactlyWhenTheirVoxelsAreEqual) {
  // How the mesher skips a brick stored again unchanged (a brush preview
  // brushing its path again).
  const VolumeOptions options{.brick_edge = 16, .levels = 4};
  Volume v = Volume::from_dense(sphere_density(40), options);
  const Volume before = v;
  v.edit(Box{{0, 0, 0}, {40, 40, 40}}, [](glm::ivec3, std::span<uint8_t>) {});
  DenseGrid<uint8_t> patch(glm::ivec3(1), 77);
  v.write({20, 3, 20}, patch);  // one voxel of brick (1, 0, 1)
  int same = 0;
  for (int64_t i = 0; i < v.brick_count(); ++i) {
    const glm::ivec3 b = grid_position(i, v.brick_grid());
    EXPECT_GT(v.brick_version(b), before.brick_version(b));
    const bool changed = b == glm::ivec3(1, 0, 1);
    EXPECT_EQ(v.brick(b).holds_same_voxels(before.brick(b)), !changed) << "brick " << i;
    same += changed ? 0 : 1;
  }
  EXPECT_EQ(same, v.brick_count() - 1);
  EXPECT_TRUE(Brick(3).holds_same_voxels(Brick(3)));
  EXPECT_FALSE(Brick(3).holds_same_voxels(Brick(4)));
  EXPECT_FALSE(Brick(3).holds_same_voxels(v.brick({1, 0, 1})));
  EXPECT_FALSE(v.brick({1, 0, 1}).holds_same_voxels(Brick(3)));
}

TEST(Volume, WriteReencodesOnlyTheTouchedBricks) {
  Volume v({100, 100, 100}, 0, small_bricks(32, 5));
  // 10^3 voxels at (28..38) straddle the brick edge at 32 on every axis: 8 bricks.
  DenseGrid<uint8_t> patch({10, 10, 10}, 200);
  v.write({28, 28, 28}, patch);
  const std::vector<glm::ivec3> dirty = v.take_dirty_bricks();
  std::set<std::tuple<int, int, int>> got;
  for (glm::ivec3 b : dirty)
    got.insert({b.x, b.y, b.z});
  std::set<std::tuple<int, int, int>> expected;
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 2; ++x)
        expected.insert({x, y, z});
  EXPECT_EQ(got, expected);
  EXPECT_TRUE(v.take_dirty_bricks().empty());
  EXPECT_EQ(v.brick_version({1, 1, 1}), 1u);
  EXPECT_EQ(v.brick_version({2, 2, 2}), 0u);
  EXPECT_EQ(v.voxel({28, 28, 28}), 200);
  EXPECT_EQ(v.voxel({37, 37, 37}), 200);
  EXPECT_EQ(v.voxel({38, 37, 37}), 0);
  EXPECT_EQ(v.voxel({27, 30, 30}), 0);
}

TEST(Volume, WritePastTheFarFaceIsClippedAndPaddingStaysConsistent) {
  const DenseGrid<uint8_t> g = random_grid({37, 37, 37}, 8);
  Volume v = Volume::from_dense(g, small_bricks(16, 4));
  DenseGrid<uint8_t> patch({10, 10, 10}, 9);
  v.write({33, 33, 33}, patch);  // 4 voxels inside, 6 outside per axis
  DenseGrid<uint8_t> expected = g;
  for (int z = 33; z < 37; ++z)
    for (int y = 33; y < 37; ++y)
      for (int x = 33; x < 37; ++x)
        expected.at(x, y, z) = 9;
  EXPECT_EQ(v.to_dense(0), expected);
  for (int level = 1; level <= 4; ++level)
    EXPECT_EQ(v.to_dense(level), reference_level(expected, level));
}

TEST(Volume, StoringAChangedBoxEqualsStoringTheBrick) {
  // Interior bricks take the partial re-encode, far-face (padded) bricks the
  // whole one; either way the volume equals one that stored whole bricks,
  // coefficient for coefficient, and versions and dirty marks follow.
  const DenseGrid<uint8_t> g = random_grid({40, 40, 40}, 21);
  Volume part = Volume::from_dense(g, small_bricks(16, 4));
  Volume full = part;
  std::vector<uint8_t> voxels(16 * 16 * 16);
  for (const glm::ivec3 b : {glm::ivec3(0, 0, 0), glm::ivec3(1, 0, 1), glm::ivec3(2, 2, 2)}) {
    part.decode_brick(b, voxels);
    const Box changed{b * 16 + glm::ivec3(3, 5, 2), b * 16 + glm::ivec3(9, 6, 12)};
    for (int z = changed.lo.z; z < changed.hi.z; ++z)
      for (int y = changed.lo.y; y < changed.hi.y; ++y)
        for (int x = changed.lo.x; x < changed.hi.x; ++x) {
          const glm::ivec3 l = glm::ivec3(x, y, z) - b * 16;
          voxels[(static_cast<size_t>(l.z) * 16 + l.y) * 16 + l.x] ^= 0x5A;
        }
    std::vector<uint8_t> copy = voxels;
    part.store_brick(b, voxels, changed);
    full.store_brick(b, copy);
    ASSERT_FALSE(part.brick(b).is_uniform());
    EXPECT_TRUE(std::ranges::equal(part.brick(b).pyramid()->coefficients(),
                                   full.brick(b).pyramid()->coefficients()))
        << b.x << " " << b.y << " " << b.z;
    EXPECT_EQ(part.brick_version(b), full.brick_version(b));
  }
  EXPECT_EQ(part.take_dirty_bricks(), full.take_dirty_bricks());
  EXPECT_EQ(part.content_hash(), full.content_hash());
  EXPECT_EQ(part.to_dense(0), full.to_dense(0));
}

TEST(Volume, StoringBricksTogetherEqualsStoringThemOneByOne) {
  // A big dab's stores: re-encoded on two threads, then counted in order.
  // The result is the stores one by one: coefficients, versions, the dirty
  // list and the voxels read back, including a brick that was among the
  // recently stored (decoded) ones before and is stored again early in the
  // batch, whose old decoded voxels must not be read.
  const DenseGrid<uint8_t> g = random_grid({100, 100, 100}, 33);  // 7^3 bricks, far faces padded
  Volume together = Volume::from_dense(g, small_bricks(16, 4));
  const glm::ivec3 early{1, 1, 1};
  std::vector<glm::ivec3> bricks{early};
  for (int i = 0; i < 29; ++i)
    bricks.push_back({i % 7, (i / 7) % 7, 3 + i % 4});
  // Among the recent ones before the batch: the first brick the batch keeps
  // decoded, then `early`. The batch's other kept stores then take every
  // slot but `early`'s, so only dropping it keeps its old voxels from being
  // read.
  const glm::ivec3 first_kept = bricks[bricks.size() - Volume::kRecentBricks];
  std::vector<uint8_t> voxels(16 * 16 * 16);
  for (const glm::ivec3 b : {first_kept, early}) {
    together.decode_brick(b, voxels);
    voxels[0] ^= 1;
    together.store_brick(b, voxels);
  }
  Volume apart = together;

  std::mt19937 rng(34);
  std::uniform_int_distribution<int> corner(0, 15);
  std::vector<std::vector<uint8_t>> batch_voxels;
  std::vector<Volume::BrickStore> batch;
  batch_voxels.reserve(bricks.size());
  for (const glm::ivec3 b : bricks) {
    std::vector<uint8_t> v(voxels.size());
    together.decode_brick(b, v);
    glm::ivec3 lo{corner(rng), corner(rng), corner(rng)}, hi{corner(rng), corner(rng), corner(rng)};
    const glm::ivec3 a = glm::min(lo, hi), c = glm::max(lo, hi) + 1;
    for (int z = a.z; z < c.z; ++z)
      for (int y = a.y; y < c.y; ++y)
        for (int x = a.x; x < c.x; ++x)
          v[(static_cast<size_t>(z) * 16 + y) * 16 + x] ^= 0x3C;
    batch_voxels.push_back(std::move(v));
    batch.push_back({b, batch_voxels.back(), Box{b * 16 + a, b * 16 + c}});
  }
  for (const Volume::BrickStore& s : batch) {
    std::vector<uint8_t> copy(s.voxels.begin(), s.voxels.end());
    apart.store_brick(s.brick, copy, s.changed);
  }
  together.store_bricks(batch, 2);

  std::vector<uint8_t> read_together(voxels.size()), read_apart(voxels.size()),
      decoded(voxels.size());
  for (int64_t i = 0; i < together.brick_count(); ++i) {
    const glm::ivec3 b{int(i % 7), int(i / 7 % 7), int(i / 49)};
    EXPECT_EQ(together.brick_version(b), apart.brick_version(b)) << i;
    together.decode_brick(b, read_together);
    apart.decode_brick(b, read_apart);
    together.brick(b).extract_level(0, decoded);
    ASSERT_EQ(read_together, read_apart) << "brick " << i;
    ASSERT_EQ(read_together, decoded) << "brick " << i << ": a stale decoded copy";
  }
  EXPECT_EQ(together.take_dirty_bricks(), apart.take_dirty_bricks());
  EXPECT_EQ(together.content_hash(), apart.content_hash());
}

TEST(Volume, ACopySharesItsBricksAndKeepsItsVoxelsWhileTheOriginalIsEdited) {
  // The autosave's copy, the mesher's bricks and the undo history's: each
  // shares the pyramids (copy on write) and must read what was copied.
  const DenseGrid<uint8_t> g = random_grid({40, 40, 40}, 33);
  Volume v = Volume::from_dense(g, small_bricks(16, 4));
  const Volume copy = v;
  for (int64_t i = 0; i < v.brick_count(); ++i) {
    const glm::ivec3 b = grid_position(i, v.brick_grid());
    ASSERT_FALSE(v.brick(b).is_uniform());
    EXPECT_EQ(copy.brick(b).pyramid(), v.brick(b).pyramid()) << "brick " << i;
    EXPECT_TRUE(v.brick(b).shares_pyramid());
  }
  const uint64_t copied_hash = copy.content_hash();

  // A changed box (re-encoded in place of a shared pyramid: copied first),
  // a whole brick, and a brick made uniform.
  std::vector<uint8_t> voxels(16 * 16 * 16);
  const glm::ivec3 in_part(1, 1, 1);
  v.decode_brick(in_part, voxels);
  const Box changed{glm::ivec3(20, 21, 22), glm::ivec3(25, 23, 30)};
  for (int z = changed.lo.z; z < changed.hi.z; ++z)
    for (int y = changed.lo.y; y < changed.hi.y; ++y)
      for (int x = changed.lo.x; x < changed.hi.x; ++x)
        voxels[(static_cast<size_t>(z - 16) * 16 + (y - 16)) * 16 + (x - 16)] ^= 0x3C;
  v.store_brick(in_part, voxels, changed);
  v.write({0, 0, 0}, random_grid({16, 16, 16}, 34));
  v.write({16, 0, 0}, DenseGrid<uint8_t>({16, 16, 16}, 200));
  EXPECT_TRUE(v.brick({1, 0, 0}).is_uniform());

  EXPECT_EQ(copy.content_hash(), copied_hash);
  EXPECT_EQ(copy.to_dense(0), g);
  for (const glm::ivec3 b : {in_part, glm::ivec3(0, 0, 0)}) {
    EXPECT_NE(v.brick(b).pyramid(), copy.brick(b).pyramid());
    EXPECT_FALSE(v.brick(b).shares_pyramid());
  }
  EXPECT_EQ(v.brick({2, 2, 2}).pyramid(), copy.brick({2, 2, 2}).pyramid());  // untouched
  // What was stored is what a volume encoded from scratch holds.
  const Volume fresh = Volume::from_dense(v.to_dense(0), small_bricks(16, 4));
  EXPECT_EQ(v.content_hash(), fresh.content_hash());
  for (int64_t i = 0; i < v.brick_count(); ++i) {
    const glm::ivec3 b = grid_position(i, v.brick_grid());
    EXPECT_TRUE(v.brick(b).holds_same_voxels(fresh.brick(b))) << "brick " << i;
  }

  // A brick of its own is re-encoded in its own storage, not copied again.
  const WaveletPyramid* own = v.brick(in_part).pyramid();
  v.store_brick(in_part, voxels, changed);
  EXPECT_EQ(v.brick(in_part).pyramid(), own);
}

TEST(Volume, ACopyIsReadOnAnotherThreadWhileTheOriginalIsEdited) {
  // The station's mesher and autosave read their copies on their own
  // threads while the sculpting thread goes on (ThreadSanitizer runs this).
  const DenseGrid<uint8_t> g = random_grid({48, 48, 48}, 35);
  Volume v = Volume::from_dense(g, small_bricks(16, 4));
  std::vector<Volume> copies;
  for (int round = 0; round < 4; ++round) {
    copies.push_back(v);
    const Volume& copy = copies.back();
    const uint64_t want = copy.content_hash();
    uint64_t read = 0;
    std::thread reader([&] {
      for (int i = 0; i < 3; ++i)
        read = copy.content_hash();
    });
    for (int i = 0; i < 20; ++i)
      v.write({(round * 7 + i * 5) % 40, (i * 11) % 40, (i * 3) % 40},
              DenseGrid<uint8_t>({8, 8, 8}, static_cast<uint8_t>(round * 20 + i)));
    reader.join();
    EXPECT_EQ(read, want) << "round " << round;
  }
  for (size_t i = 1; i < copies.size(); ++i)
    EXPECT_NE(copies[i].content_hash(), copies[i - 1].content_hash());
}

TEST(Volume, UniformBricksCostConstantMemory) {
  const Volume empty({1024, 1024, 1024}, 0);
  const VolumeStats s = empty.stats();
  EXPECT_EQ(s.bricks, 32 * 32 * 32);
  EXPECT_EQ(s.uniform_bricks, s.bricks);
  EXPECT_LT(s.memory_bytes, size_t{4} << 20);  // a few bytes per brick, not 1 GiB
}

TEST(Volume, MemoryGrowsWithTheSurfaceNotTheBox) {
  const VolumeStats small = sphere_volume(128).stats();
  const VolumeStats large = sphere_volume(256).stats();
  // The sphere's surface grows 4x when its box grows 8x: so must the memory.
  const double ratio =
      static_cast<double>(large.memory_bytes) / static_cast<double>(small.memory_bytes);
  EXPECT_GT(ratio, 2.5);
  EXPECT_LT(ratio, 5.5);
  EXPECT_GT(large.uniform_bricks, large.bricks / 2);
}

TEST(Volume, EditSeesAndKeepsNeighbouringContent) {
  Volume v = Volume::from_dense(random_grid({64, 64, 64}, 1), small_bricks(32, 5));
  const DenseGrid<uint8_t> before = v.to_dense();
  v.edit(Box{{10, 10, 10}, {40, 12, 12}}, [](glm::ivec3, std::span<uint8_t>) {});
  EXPECT_EQ(v.to_dense(), before);  // a no-op edit is bit-exact
  EXPECT_EQ(v.take_dirty_bricks().size(), 2u);
}

TEST(Volume, ValidateNamesWhatIsOutOfRange) {
  EXPECT_FALSE(Volume::validate({0, 10, 10}, {}).ok());
  EXPECT_FALSE(Volume::validate({100000, 100000, 100000}, {}).ok());
  // 2^32 voxels at most: 65536 x 65536 x 1 fits, x 2 does not.
  EXPECT_TRUE(Volume::validate({65536, 65536, 1}, {}).ok());
  EXPECT_NE(Volume::validate({65536, 65536, 2}, {}).error().message().find("4294967296"),
            std::string::npos);
  VolumeOptions bad_edge;
  bad_edge.brick_edge = 24;
  EXPECT_NE(Volume::validate({10, 10, 10}, bad_edge).error().message().find("power of two"),
            std::string::npos);
  VolumeOptions too_many_levels;
  too_many_levels.brick_edge = 16;
  too_many_levels.levels = 5;
  EXPECT_NE(Volume::validate({10, 10, 10}, too_many_levels).error().message().find("levels"),
            std::string::npos);
  EXPECT_TRUE(Volume::validate({10, 10, 10}, {}).ok());
}

}  // namespace
}  // namespace sculpt::core
