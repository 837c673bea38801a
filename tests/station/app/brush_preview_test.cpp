// BrushPreview: a preview is put back exactly, and a preview followed by the
// real stroke leaves what the stroke alone leaves.

#include "sculpt/station/app/brush_preview.h"

#include <gtest/gtest.h>

#include <vector>

#include "sculpt/core/grid/dense_grid.h"
#include "sculpt/core/sculpt/clay_brush.h"
#include "sculpt/core/sculpt/grab_brush.h"
#include "sculpt/core/sculpt/sculptor.h"

namespace sculpt::station {
namespace {

// A 64^3 block, a slab of material below z = 40.
core::Volume slab() {
  core::Volume v(glm::ivec3(64), 0);
  core::DenseGrid<uint8_t> material(glm::ivec3(64, 64, 40), 255);
  v.write(glm::ivec3(0), material);
  return v;
}

std::vector<core::StrokeSample> path(int samples) {
  std::vector<core::StrokeSample> p;
  for (int i = 0; i < samples; ++i)
    p.push_back({glm::vec3(16.0f + 2.0f * static_cast<float>(i), 32.0f,
                           40.0f + 0.5f * static_cast<float>(i)),
                 {}});
  return p;
}

core::Box reach(const std::vector<core::StrokeSample>& p, float radius) {
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const auto& s : p) {
    lo = glm::min(lo, s.position_vox);
    hi = glm::max(hi, s.position_vox);
  }
  return core::Box{glm::ivec3(glm::floor(lo - radius - 2.0f)),
                   glm::ivec3(glm::ceil(hi + radius + 2.0f)) + 1};
}

TEST(BrushPreview, DueAfterTwoSamplesThenAsThePathGrowsByAnEighth) {
  EXPECT_FALSE(BrushPreview::due(1, 0));
  EXPECT_TRUE(BrushPreview::due(2, 0));
  EXPECT_FALSE(BrushPreview::due(3, 2));
  EXPECT_TRUE(BrushPreview::due(4, 2));
  EXPECT_FALSE(BrushPreview::due(100, 90));
  EXPECT_TRUE(BrushPreview::due(101, 90));
  // A long stroke: the path grows by an eighth between previews, so a
  // thousand samples take a few dozen, not hundreds.
  size_t shown = 0, previews = 0;
  for (size_t n = 1; n <= 1000; ++n)
    if (BrushPreview::due(n, shown)) {
      shown = n;
      ++previews;
    }
  EXPECT_LE(previews, 48u);
}

TEST(BrushPreview, RevertPutsTheMaterialBackExactlyAndTouchesOnlyChangedBricks) {
  core::Volume v = slab();
  const uint64_t before = v.content_hash();
  const std::vector<core::StrokeSample> p = path(8);
  // Kept more than the brush reaches: bricks it does not store.
  const core::Box region = core::intersect(reach(p, 30.0f), core::Box{glm::ivec3(0), v.dims()});
  const core::Box bricks = v.bricks_overlapping(region);
  auto versions = [&] {
    std::vector<uint64_t> out;
    for (int z = bricks.lo.z; z < bricks.hi.z; ++z)
      for (int y = bricks.lo.y; y < bricks.hi.y; ++y)
        for (int x = bricks.lo.x; x < bricks.hi.x; ++x)
          out.push_back(v.brick_version({x, y, z}));
    return out;
  };
  const std::vector<uint64_t> kept = versions();
  BrushPreview preview;
  const int64_t changed = preview.show(v, region, p.size(), [&] {
    core::Sculptor scratch(v);
    core::ClayBrushOptions o;
    o.radius_vox = 6.0f;
    return core::clay_stroke(v, scratch, p, o);
  });
  EXPECT_GT(changed, 0);
  EXPECT_NE(v.content_hash(), before);
  EXPECT_TRUE(preview.active());
  EXPECT_EQ(preview.shown_samples(), p.size());
  const std::vector<uint64_t> shown = versions();
  preview.revert(v);
  EXPECT_FALSE(preview.active());
  EXPECT_EQ(preview.shown_samples(), 0u);
  EXPECT_EQ(v.content_hash(), before);
  // Bricks the preview did not store are not stored again.
  const std::vector<uint64_t> after = versions();
  int untouched = 0;
  for (size_t i = 0; i < kept.size(); ++i)
    if (shown[i] == kept[i]) {
      EXPECT_EQ(after[i], kept[i]);
      ++untouched;
    }
  EXPECT_GT(untouched, 0);
}

TEST(BrushPreview, PreviewsThenTheStrokeLeaveWhatTheStrokeAloneLeaves) {
  const std::vector<core::StrokeSample> full = path(12);
  core::GrabBrushOptions o;
  o.radius_vox = 5.0f;
  // The stroke alone.
  core::Volume alone = slab();
  {
    core::Sculptor s(alone);
    ASSERT_GT(core::grab_stroke(alone, s, full, o), 0);
  }
  // Previews of growing prefixes, then the stroke, as the station does it.
  core::Volume live = slab();
  core::Sculptor sculptor(live);
  BrushPreview preview;
  for (size_t n = 1; n <= full.size(); ++n) {
    if (!BrushPreview::due(n, preview.shown_samples())) continue;
    const std::vector<core::StrokeSample> prefix(full.begin(), full.begin() + n);
    preview.show(live, reach(prefix, o.radius_vox), n, [&] {
      core::Sculptor scratch(live);
      return core::grab_stroke(live, scratch, prefix, o);
    });
  }
  preview.revert(live);
  core::grab_stroke(live, sculptor, full, o);
  EXPECT_EQ(live.content_hash(), alone.content_hash());
  // One undo step: undoing it gives the slab back.
  EXPECT_TRUE(sculptor.undo());
  EXPECT_EQ(live.content_hash(), slab().content_hash());
  EXPECT_FALSE(sculptor.undo());
}

}  // namespace
}  // namespace sculpt::station
