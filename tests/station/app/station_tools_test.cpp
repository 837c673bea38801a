// Tools in the window (issue 23): a region of the sculpture picked as the
// tool, tools at another size, a new block, offset and closing of the
// sculpture, each through the controller as the panel and keys call it.

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <thread>

#include "scratch_dir.h"
#include "sculpt/core/files/volume_file.h"
#include "sculpt/core/mesh/mesh_io.h"
#include "sculpt/core/volume/material_bounds.h"
#include "sculpt/sim/session/session_file.h"
#include "sculpt/station/app/session_replay.h"
#include "sculpt/station/app/session_start.h"
#include "sculpt/station/app/station_controller.h"
#include "sculpt/station/view/tool_outline.h"
#include "small_block.h"

namespace sculpt::station {
namespace {

constexpr int64_t kMs = 1'000'000;

// The 64^3 test block with its slab of clay, or empty (margin 0).
ControllerOptions block(const test::ScratchDir& dir, int clay_margin = 12) {
  ControllerOptions o = test_blocks::small_block(dir);
  o.loop.clay_margin = clay_margin;
  o.autosave_seconds = 0.0;
  return o;
}

::testing::AssertionResult same_voxels(const core::DenseGrid<uint8_t>& a,
                                       const core::DenseGrid<uint8_t>& b) {
  if (a.dims() != b.dims()) return ::testing::AssertionFailure() << "the grids differ in size";
  if (!std::equal(a.data(), a.data() + a.size(), b.data()))
    return ::testing::AssertionFailure() << "the voxels differ";
  return ::testing::AssertionSuccess();
}

// The recording at `path` replayed, from its saved start when it has one.
void replay(const std::filesystem::path& path, StationLoop& loop) {
  auto session = sim::read_session_file(path);
  ASSERT_TRUE(session.ok()) << session.error().message();
  const Result<bool> started = restore_session_start(path, loop);
  ASSERT_TRUE(started.ok()) << started.error().message();
  const auto r = replay_session(*session, path.string(), loop);
  ASSERT_TRUE(r.ok()) << r.error().message();
}

// Ends the recording, replays it into `replayed` and checks the replay ends
// as the station did: the same volume hash and the same tool, bit for bit.
void stop_and_replay(StationController& c, int64_t t, const test::ScratchDir& dir,
                     StationLoop& replayed) {
  c.tick(t);
  ASSERT_TRUE(c.stop_recording().ok());
  replay(dir.path() / "r.scs", replayed);
  EXPECT_EQ(replayed.volume().content_hash(), c.loop().volume().content_hash());
  EXPECT_TRUE(same_voxels(replayed.tool().density, c.loop().tool().density));
}

// A mouse stroke across the clay's top face (z = 51), so the region holds
// more than a plain slab.
void stroke(StationController& c, int64_t& t, float y, float z = 52.0f) {
  c.pointer_move({20.0f, y, z}, t += kMs);
  c.pointer_down(t += kMs);
  for (int i = 0; i <= 20; ++i)
    c.pointer_move({20.0f + static_cast<float>(i), y, z}, t += kMs);
  c.pointer_up(t += kMs);
}

TEST(StationTools, ARegionToolEqualsTheRegionsVoxels) {
  test::ScratchDir dir;
  StationController c(block(dir));
  int64_t t = 1000 * kMs;
  c.set_tool(sim::ToolShape::kSphere, 3.0f, 0.0f, t += kMs);
  stroke(c, t, 30.0f);
  const core::Box region{{16, 24, 40}, {44, 38, 56}};
  c.set_tool_region(region);
  ASSERT_TRUE(c.use_region_as_tool(t += kMs)) << c.status();
  EXPECT_EQ(c.status(), "the region is the tool now (28x14x16 voxels)");
  EXPECT_TRUE(same_voxels(c.loop().tool().density, c.loop().volume().read(region)));
  EXPECT_TRUE(c.loop().settings().custom_tool);
  EXPECT_EQ(c.loop().settings().custom_region, region);
}

TEST(StationTools, TheRegionStartsFromTheMaterialOrAroundTheTool) {
  test::ScratchDir dir;
  StationController c(block(dir));
  EXPECT_FALSE(c.tool_region().has_value());
  EXPECT_TRUE(c.perform(Action::kToggleToolRegion, 0));
  ASSERT_TRUE(c.tool_region().has_value());
  EXPECT_EQ(*c.tool_region(), *core::material_bounds(c.loop().volume()));
  EXPECT_TRUE(c.perform(Action::kToggleToolRegion, 0));
  EXPECT_FALSE(c.tool_region().has_value());

  c.pointer_move({30.0f, 30.0f, 30.0f}, kMs);
  c.tool_region_around_tool();  // a radius-8 sphere: 16 voxels across
  ASSERT_TRUE(c.tool_region().has_value());
  EXPECT_EQ(c.tool_region()->lo, glm::ivec3(22));
  EXPECT_EQ(c.tool_region()->hi, glm::ivec3(38));
  // Corners beyond the block are clamped to it.
  c.set_tool_region({{-5, 10, 10}, {20, 99, 20}});
  EXPECT_EQ(c.tool_region()->lo, glm::ivec3(0, 10, 10));
  EXPECT_EQ(c.tool_region()->hi, glm::ivec3(20, 64, 20));
}

TEST(StationTools, ABadRegionIsOneClearMessageAndNoTool) {
  test::ScratchDir dir;
  StationController c(block(dir));
  EXPECT_FALSE(c.use_region_as_tool(0));
  EXPECT_EQ(c.status(), "no tool region: pick one first");
  EXPECT_FALSE(c.perform(Action::kUseRegionAsTool, 0));

  c.set_tool_region({{30, 30, 30}, {30, 40, 40}});
  EXPECT_FALSE(c.use_region_as_tool(0));
  EXPECT_EQ(c.status(), "the region is empty: no voxel of the block is in it");

  c.set_tool_region({{0, 0, 0}, {8, 8, 8}});  // the margin: no clay
  EXPECT_FALSE(c.use_region_as_tool(0));
  EXPECT_EQ(c.status(), "the region holds no material: no tool made of it");

  ControllerOptions big = block(dir);
  big.loop.volume_dims = glm::ivec3(128);
  StationController b(big);
  b.set_tool_region({{0, 0, 0}, {128, 20, 20}});
  EXPECT_FALSE(b.use_region_as_tool(0));
  EXPECT_EQ(b.status(),
            "the region (128x20x20 voxels) is too big for a tool: at most 96 voxels a side");
  EXPECT_FALSE(c.loop().settings().custom_tool);
  EXPECT_FALSE(b.loop().settings().custom_tool);
}

TEST(StationTools, ARegionToolReplaysBitForBit) {
  test::ScratchDir dir;
  StationController c(block(dir));
  int64_t t = 1000 * kMs;
  ASSERT_TRUE(c.start_recording(dir.path() / "r.scs", t).ok());
  c.set_tool(sim::ToolShape::kSphere, 3.0f, 0.0f, t += kMs);
  stroke(c, t, 30.0f);
  c.set_tool_region({{18, 26, 44}, {30, 36, 56}});
  ASSERT_TRUE(c.perform(Action::kUseRegionAsTool, t += kMs)) << c.status();
  c.set_mode(core::SculptMode::kSubtract, t += kMs);
  stroke(c, t, 20.0f);
  StationLoop replayed(StationLoop::Options{});
  stop_and_replay(c, t, dir, replayed);
}

double density_sum(const core::Tool& tool) {
  double sum = 0;
  for (size_t i = 0; i < tool.density.size(); ++i)
    sum += tool.density.data()[i];
  return sum;
}

// A ball of `radius` dabbed into an empty block, its region made the tool.
void ball_region_tool(StationController& c, int64_t& t, int radius = 6) {
  c.set_tool(sim::ToolShape::kSphere, static_cast<float>(radius), 0.0f, t += kMs);
  c.pointer_move({32.0f, 32.0f, 32.0f}, t += kMs);
  c.pointer_down(t += kMs);
  c.pointer_up(t += kMs);
  c.set_tool_region({glm::ivec3(30 - radius), glm::ivec3(35 + radius)});
  ASSERT_TRUE(c.use_region_as_tool(t += kMs)) << c.status();
}

TEST(StationTools, AScaledCustomToolKeepsItsShape) {
  test::ScratchDir dir;
  StationController c(block(dir, 0));
  int64_t t = 1000 * kMs;
  ball_region_tool(c, t, 10);
  const double made = density_sum(c.loop().tool());
  ASSERT_GT(made, 0.0);
  const glm::dvec3 made_dims(c.loop().tool().density.dims());
  for (const float f : {2.0f, 0.5f, 1.5f, 3.0f}) {
    ASSERT_TRUE(c.set_tool_scale(f, t += kMs)) << c.status();
    EXPECT_EQ(c.loop().settings().tool_scale, f);
    // The grid takes round(25 f) voxels a side, so the shape scales by
    // that over 25 on each axis (f itself when 25 f is whole).
    const glm::dvec3 s = glm::dvec3(c.loop().tool().density.dims()) / made_dims;
    const double analytic = s.x * s.y * s.z;
    EXPECT_NEAR(density_sum(c.loop().tool()) / made, analytic, 0.01 * analytic) << f;
  }
  // Back to 1: the tool as made, bit for bit (scales never compound).
  ASSERT_TRUE(c.set_tool_scale(1.0f, t += kMs));
  EXPECT_TRUE(same_voxels(c.loop().tool().density,
                          c.loop().volume().read({glm::ivec3(20), glm::ivec3(45)})));
}

TEST(StationTools, TheSizeKeysScaleACustomToolAndItsLimitsAreOneMessage) {
  test::ScratchDir dir;
  StationController c(block(dir, 0));
  int64_t t = 1000 * kMs;
  EXPECT_FALSE(c.set_tool_scale(2.0f, t));
  EXPECT_EQ(c.status(), "a built-in tool changes size by its sizes, not a scale");
  ball_region_tool(c, t);
  ASSERT_TRUE(c.perform(Action::kToolBigger, t += kMs)) << c.status();
  EXPECT_EQ(c.loop().settings().tool_scale, 1.25f);
  EXPECT_EQ(c.loop().tool().density.dims(), glm::ivec3(21));  // round(17 x 1.25)
  EXPECT_EQ(c.status(), "the tool at 1.25 times its size: 21x21x21 voxels");
  ASSERT_TRUE(c.perform(Action::kToolSmaller, t += kMs));
  EXPECT_EQ(c.loop().settings().tool_scale, 1.0f);
  EXPECT_TRUE(c.set_tool_scale(0.01f, t += kMs)) << c.status();  // clamped to 1/8
  EXPECT_EQ(c.loop().settings().tool_scale, 0.125f);
  // A 30^3 region at 8 times (clamped from 12): 240 voxels a side, over the largest tool.
  c.set_tool_region({{10, 10, 10}, {40, 40, 40}});
  ASSERT_TRUE(c.use_region_as_tool(t += kMs)) << c.status();
  EXPECT_FALSE(c.set_tool_scale(12.0f, t += kMs));
  EXPECT_EQ(c.status(),
            "the tool at 8 times its size would be 240x240x240 voxels: at most 192 a side");
  EXPECT_EQ(c.loop().tool().density.dims(), glm::ivec3(30));
  EXPECT_EQ(c.loop().settings().tool_scale, 1.0f);
  // A built-in tool again: the scale is the custom tool's only.
  c.set_tool(sim::ToolShape::kCube, 6.0f, 0.0f, t += kMs);
  EXPECT_FALSE(c.loop().settings().custom_tool);
  ASSERT_TRUE(c.perform(Action::kToolBigger, t += kMs));
  EXPECT_EQ(c.loop().settings().size_a_vox, 7.5f);
  EXPECT_FALSE(c.loop().settings().custom_tool);
}

// A 12x10x12 region of the slab's top made the tool, at 1.5 times its size.
void region_tool_at_one_and_a_half(StationController& c, int64_t& t) {
  c.set_tool_region({{18, 26, 44}, {30, 36, 56}});
  ASSERT_TRUE(c.use_region_as_tool(t += kMs)) << c.status();
  ASSERT_TRUE(c.set_tool_scale(1.5f, t += kMs));
}

TEST(StationTools, AScaledToolReplaysAndReopensBitForBit) {
  test::ScratchDir dir;
  StationController c(block(dir));
  int64_t t = 1000 * kMs;
  region_tool_at_one_and_a_half(c, t);
  // A recording started now opens with the custom tool at its scale (the
  // sculpture saved beside it), not the built-in shape.
  ASSERT_TRUE(c.start_recording(dir.path() / "r.scs", t += kMs).ok()) << c.status();
  c.set_mode(core::SculptMode::kSubtract, t += kMs);
  stroke(c, t, 20.0f);
  ASSERT_TRUE(c.set_tool_scale(0.75f, t += kMs));
  stroke(c, t, 40.0f);
  EXPECT_TRUE(c.loop().settings().custom_tool);
  StationLoop replayed(StationLoop::Options{});
  stop_and_replay(c, t, dir, replayed);
  EXPECT_EQ(replayed.settings().tool_scale, 0.75f);

  // A project keeps the tool as made and its scale.
  ASSERT_TRUE(c.save(dir.path() / "p.sculpt").ok());
  StationController reopened(block(dir));
  ASSERT_TRUE(reopened.open(dir.path() / "p.sculpt").ok()) << reopened.status();
  EXPECT_EQ(reopened.loop().settings().tool_scale, 0.75f);
  EXPECT_TRUE(same_voxels(reopened.loop().tool().density, c.loop().tool().density));
}

TEST(StationTools, ANewBlockReplacesTheSculptureAndReplays) {
  test::ScratchDir dir;
  StationController c(block(dir));
  int64_t t = 1000 * kMs;
  ASSERT_TRUE(c.start_recording(dir.path() / "r.scs", t).ok());
  stroke(c, t, 30.0f);
  c.perform(Action::kToggleToolRegion, t);
  ASSERT_TRUE(c.new_block({{48, 40, 32}, BlockFill::kFull}, t += kMs)) << c.status();
  EXPECT_EQ(c.status(), "a new block of 48x40x32 voxels, full (the undo history starts here)");
  EXPECT_EQ(c.loop().volume().dims(), glm::ivec3(48, 40, 32));
  EXPECT_EQ(c.loop().volume().voxel({0, 0, 0}), 255);
  EXPECT_EQ(c.loop().volume().content_hash(), core::Volume({48, 40, 32}, 255).content_hash());
  EXPECT_FALSE(c.tool_region().has_value());  // it may lie outside the new block
  c.undo(t += kMs);
  EXPECT_EQ(c.status(), "nothing to undo");
  EXPECT_EQ(c.loop().volume().voxel({0, 0, 0}), 255);
  // The panel's choice through the key's action; a clay slab.
  c.new_block_options() = {{40, 40, 40}, BlockFill::kClay};
  ASSERT_TRUE(c.perform(Action::kNewBlock, t += kMs)) << c.status();
  EXPECT_EQ(c.loop().volume().voxel({20, 20, 20}), 255);
  EXPECT_EQ(c.loop().volume().voxel({2, 2, 2}), 0);
  c.set_mode(core::SculptMode::kSubtract, t += kMs);
  stroke(c, t, 30.0f);
  ASSERT_TRUE(c.new_block({{32, 32, 32}, BlockFill::kEmpty}, t += kMs));
  EXPECT_FALSE(core::material_bounds(c.loop().volume()).has_value());
  c.set_mode(core::SculptMode::kAdd, t += kMs);
  stroke(c, t, 20.0f);
  c.tick(t);
  ASSERT_TRUE(c.stop_recording().ok());

  StationLoop replayed(StationLoop::Options{});
  replay(dir.path() / "r.scs", replayed);
  EXPECT_EQ(replayed.volume().dims(), glm::ivec3(32));
  EXPECT_EQ(replayed.volume().content_hash(), c.loop().volume().content_hash());
}

TEST(StationTools, ANewBlockOfABadSizeIsOneMessageAndChangesNothing) {
  test::ScratchDir dir;
  StationController c(block(dir));
  const uint64_t before = c.loop().volume().content_hash();
  EXPECT_FALSE(c.new_block({{4, 64, 64}, BlockFill::kFull}, 0));
  EXPECT_EQ(c.status(), "a block of 4x64x64 voxels: each side must be 8 to 1024 voxels");
  EXPECT_FALSE(c.new_block({{64, 2048, 64}, BlockFill::kEmpty}, 0));
  EXPECT_EQ(c.loop().volume().content_hash(), before);
}

// Offset and closing (issue 23): each one undo step that gives the exact
// sculpture back, recorded and replayed to the same hash.
TEST(StationTools, OffsetAndClosingAreOneUndoStepEachAndReplay) {
  test::ScratchDir dir;
  StationController c(block(dir));
  int64_t t = 1000 * kMs;
  ASSERT_TRUE(c.start_recording(dir.path() / "r.scs", t).ok());
  // A groove 3 voxels wide and 3 deep across the slab's top, for the
  // closing to fill.
  c.set_tool(sim::ToolShape::kSphere, 1.5f, 0.0f, t += kMs);
  c.set_mode(core::SculptMode::kSubtract, t += kMs);
  stroke(c, t, 30.0f, 50.0f);
  const uint64_t grooved = c.loop().volume().content_hash();
  ASSERT_LT(c.loop().volume().voxel({30, 30, 49}), 128);
  ASSERT_EQ(c.loop().volume().voxel({30, 30, 50}), 0);

  ASSERT_TRUE(c.offset_sculpture(2.0f, t += kMs)) << c.status();
  const MorphologyResult grown = c.loop().last_morphology();
  EXPECT_GT(grown.inside_after, grown.inside_before);
  EXPECT_NE(c.status().find("offset by +2 voxels: "), std::string::npos) << c.status();
  const uint64_t offset = c.loop().volume().content_hash();
  EXPECT_NE(offset, grooved);
  c.undo(t += kMs);
  EXPECT_EQ(c.loop().volume().content_hash(), grooved);
  c.redo(t += kMs);
  EXPECT_EQ(c.loop().volume().content_hash(), offset);
  c.undo(t += kMs);

  c.closing_radius_vox() = 3.0f;
  ASSERT_TRUE(c.perform(Action::kCloseSculpture, t += kMs)) << c.status();
  const MorphologyResult closed = c.loop().last_morphology();
  EXPECT_GT(closed.inside_after, closed.inside_before);  // the groove filled
  // The groove's bottom is material again (its top within a voxel of the
  // slab's face); above the face stays empty.
  EXPECT_GT(c.loop().volume().voxel({30, 30, 49}), 127);
  EXPECT_GT(c.loop().volume().voxel({30, 30, 50}), 100);
  EXPECT_LT(c.loop().volume().voxel({30, 30, 54}), 128);
  const uint64_t closed_hash = c.loop().volume().content_hash();
  c.undo(t += kMs);
  EXPECT_EQ(c.loop().volume().content_hash(), grooved);
  c.redo(t += kMs);
  c.offset_vox() = -1.5f;
  ASSERT_TRUE(c.perform(Action::kOffsetSculpture, t += kMs)) << c.status();
  EXPECT_LT(c.loop().last_morphology().inside_after, c.loop().last_morphology().inside_before);
  c.undo(t += kMs);
  EXPECT_EQ(c.loop().volume().content_hash(), closed_hash);
  c.tick(t);
  ASSERT_TRUE(c.stop_recording().ok());

  StationLoop replayed(StationLoop::Options{});
  replay(dir.path() / "r.scs", replayed);
  EXPECT_EQ(replayed.volume().content_hash(), closed_hash);
  // And the undone offset is still there to redo in the replay.
  replayed.handle(sim::Command{sim::CommandKind::kRedo});
  c.redo(t += kMs);
  EXPECT_EQ(replayed.volume().content_hash(), c.loop().volume().content_hash());
}

// The window computes offset and closing on a worker: the call returns at
// once, the status says it computes, and whatever comes next (a stroke, an
// undo, another closing) lands it first, so every step ends as computed at
// once; recorded, it replays to the same hash.
TEST(StationTools, OffsetAndClosingInTheBackgroundLandBeforeWhatComesNext) {
  test::ScratchDir at_once_dir, background_dir;
  StationController at_once(block(at_once_dir));
  ControllerOptions o = block(background_dir);
  o.loop.background_morphology = true;
  StationController background(o);
  int64_t t = 1000 * kMs;
  ASSERT_TRUE(background.start_recording(background_dir.path() / "r.scs", t).ok());
  for (StationController* c : {&at_once, &background}) {
    int64_t tc = t;
    c->set_tool(sim::ToolShape::kSphere, 1.5f, 0.0f, tc += kMs);
    c->set_mode(core::SculptMode::kSubtract, tc += kMs);
    stroke(*c, tc, 30.0f, 50.0f);
  }
  t += 100 * kMs;
  for (StationController* c : {&at_once, &background})
    ASSERT_TRUE(c->offset_sculpture(2.0f, t)) << c->status();
  EXPECT_TRUE(background.loop().morphology_pending());
  EXPECT_EQ(background.status(), "offsetting by +2 voxels...");
  EXPECT_FALSE(background.loop().last_morphology().applied);
  // Landed when asked to wait: the status tells the result.
  EXPECT_TRUE(background.land_morphology(/*wait=*/true));
  EXPECT_FALSE(background.loop().morphology_pending());
  EXPECT_EQ(background.status(), at_once.status());
  EXPECT_EQ(background.loop().volume().content_hash(), at_once.loop().volume().content_hash());

  // A closing, then at once a stroke and an undo: each settles it first.
  for (StationController* c : {&at_once, &background}) {
    int64_t tc = t;
    c->closing_radius_vox() = 3.0f;
    ASSERT_TRUE(c->perform(Action::kCloseSculpture, tc += kMs)) << c->status();
    stroke(*c, tc, 40.0f, 55.0f);
    c->undo(tc += kMs);
    c->offset_vox() = -1.5f;
    ASSERT_TRUE(c->perform(Action::kOffsetSculpture, tc += kMs)) << c->status();
  }
  t += 100 * kMs;
  EXPECT_TRUE(background.land_morphology(/*wait=*/true));
  EXPECT_EQ(background.loop().counters().undos, at_once.loop().counters().undos);
  EXPECT_EQ(background.loop().volume().content_hash(), at_once.loop().volume().content_hash());
  // Without waiting it lands once ready; nothing is pending afterwards.
  ASSERT_TRUE(background.offset_sculpture(1.0f, t += kMs));
  while (!background.land_morphology())
    std::this_thread::yield();
  EXPECT_TRUE(background.loop().last_morphology().applied);
  StationLoop replayed(StationLoop::Options{});
  stop_and_replay(background, t, background_dir, replayed);
}

TEST(StationTools, OffsetWithoutASurfaceOrOutOfRangeIsOneMessage) {
  test::ScratchDir dir;
  StationController empty(block(dir, 0));
  EXPECT_FALSE(empty.offset_sculpture(2.0f, 0));
  EXPECT_EQ(empty.status(), "no surface to offset: the block is empty or solid");
  ASSERT_TRUE(empty.new_block({{16, 16, 16}, BlockFill::kFull}, 0));
  EXPECT_FALSE(empty.close_sculpture(2.0f, 0));
  EXPECT_EQ(empty.status(), "no surface to close: the block is empty or solid");
  EXPECT_EQ(empty.loop().volume().content_hash(), core::Volume({16, 16, 16}, 255).content_hash());
  empty.undo(0);
  EXPECT_EQ(empty.status(), "nothing to undo");

  StationController c(block(dir));
  const uint64_t before = c.loop().volume().content_hash();
  EXPECT_FALSE(c.offset_sculpture(100.0f, 0));
  EXPECT_EQ(c.status(), "no offset by 100 voxels: it takes -64 to 64 voxels, not 0");
  EXPECT_FALSE(c.close_sculpture(0.0f, 0));
  EXPECT_EQ(c.status(), "no closing by 0 voxels: it takes a radius above 0, at most 64 voxels");
  EXPECT_EQ(c.loop().volume().content_hash(), before);
}

// Tool files and meshes (issue 23): a saved tool loads back exactly, its
// voxels ride in the recording, and a replay holds the same tool.
TEST(StationTools, ASavedToolLoadsBackAndItsRecordingReplays) {
  test::ScratchDir dir;
  StationController c(block(dir));
  int64_t t = 1000 * kMs;
  region_tool_at_one_and_a_half(c, t);
  const core::Tool saved = c.loop().tool();
  ASSERT_TRUE(c.save_tool(dir.path() / "tools" / "region.nrrd").ok()) << c.status();
  EXPECT_EQ(c.status(), "tool saved to " + (dir.path() / "tools" / "region.nrrd").string() +
                            " (18x15x18 voxels)");

  ASSERT_TRUE(c.start_recording(dir.path() / "r.scs", t += kMs).ok());
  c.set_tool(sim::ToolShape::kCube, 5.0f, 0.0f, t += kMs);
  ASSERT_TRUE(c.load_tool(dir.path() / "tools" / "region.nrrd", t += kMs)) << c.status();
  EXPECT_EQ(c.status(), "region.nrrd is the tool now (18x15x18 voxels)");
  EXPECT_TRUE(same_voxels(c.loop().tool().density, saved.density));
  EXPECT_EQ(c.loop().tool().pivot, saved.pivot);
  EXPECT_EQ(c.loop().settings().custom_source, CustomToolSource::kFile);
  EXPECT_EQ(c.loop().settings().tool_scale, 1.0f);  // the file's size is its own
  c.set_mode(core::SculptMode::kSubtract, t += kMs);
  stroke(c, t, 20.0f);
  ASSERT_TRUE(c.set_tool_scale(0.5f, t += kMs));
  stroke(c, t, 40.0f);
  StationLoop replayed(StationLoop::Options{});
  stop_and_replay(c, t, dir, replayed);
  EXPECT_TRUE(same_voxels(replayed.custom_tool_base().density, saved.density));
}

TEST(StationTools, AClosedMeshBecomesTheTool) {
  test::ScratchDir dir;
  StationController c(block(dir));
  const core::Mesh ball = tool_outline(core::make_sphere_tool(12.0f));
  ASSERT_TRUE(core::check_topology(ball).closed());
  ASSERT_TRUE(core::write_mesh(dir.path() / "ball.ply", ball, core::MeshFormat::kPlyBinary).ok());
  ASSERT_TRUE(c.import_mesh_as_tool(dir.path() / "ball.ply", 32, kMs)) << c.status();
  EXPECT_EQ(c.status(), "ball.ply is the tool now (32x32x32 voxels)");
  const core::Tool& tool = c.loop().tool();
  ASSERT_EQ(tool.density.dims(), glm::ivec3(32));
  // A ball 32 - 2 x 2 voxels across, centred: its volume within 5% of the
  // analytic ball's (the mesh is the marched surface of a voxel ball).
  const double r = 0.5 * (32 - 1 - 2 * 2);
  EXPECT_NEAR(density_sum(tool) / 255.0, 4.18879 * r * r * r, 0.05 * 4.18879 * r * r * r);
  EXPECT_EQ(tool.density.at(16, 16, 16), 255);
  EXPECT_EQ(tool.density.at(0, 0, 0), 0);
}

TEST(StationTools, BadToolFilesAndMeshesAreOneMessageAndKeepTheTool) {
  test::ScratchDir dir;
  StationController c(block(dir));
  const std::filesystem::path missing = dir.path() / "missing.nrrd";
  EXPECT_FALSE(c.load_tool(missing, kMs));
  EXPECT_NE(c.status().find(missing.string()), std::string::npos) << c.status();
  EXPECT_EQ(c.status().find('\n'), std::string::npos);
  {
    std::ofstream broken(dir.path() / "broken.nrrd");
    broken << "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4\n\n";
  }
  EXPECT_FALSE(c.load_tool(dir.path() / "broken.nrrd", kMs));
  EXPECT_NE(c.status().find("broken.nrrd"), std::string::npos) << c.status();
  EXPECT_FALSE(c.import_mesh_as_tool(dir.path() / "missing.obj", 32, kMs));
  EXPECT_NE(c.status().find("missing.obj"), std::string::npos) << c.status();
  {
    std::ofstream open_mesh(dir.path() / "open.obj");
    open_mesh << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  }
  EXPECT_FALSE(c.import_mesh_as_tool(dir.path() / "open.obj", 32, kMs));
  EXPECT_NE(c.status().find("the mesh is not closed (3 boundary"), std::string::npos) << c.status();
  EXPECT_FALSE(c.import_mesh_as_tool(dir.path() / "open.obj", 4, kMs));
  EXPECT_NE(c.status().find("a mesh tool is 8 to 192 voxels a side, not 4"), std::string::npos)
      << c.status();
  // A tool file too big for a tool.
  core::Tool big = core::tool_from_grid(core::DenseGrid<uint8_t>(glm::ivec3(200, 8, 8)));
  ASSERT_TRUE(core::write_tool_file(dir.path() / "big.nrrd", big).ok());
  EXPECT_FALSE(c.load_tool(dir.path() / "big.nrrd", kMs));
  EXPECT_EQ(c.status(),
            "big.nrrd (200x8x8 voxels) is too big for a tool: at most 192 voxels a side");
  EXPECT_FALSE(c.loop().settings().custom_tool);
}

TEST(StationTools, TheToolLibraryListsToolFilesWithThumbnails) {
  test::ScratchDir dir;
  StationController c(block(dir));
  const std::filesystem::path folder = dir.path() / "tools";
  const glm::ivec3 sphere_dims = c.loop().tool().density.dims();
  ASSERT_TRUE(c.save_tool(folder / "b_sphere.nrrd").ok());
  c.set_tool(sim::ToolShape::kRing, 8.0f, 3.0f, 0);
  ASSERT_TRUE(c.save_tool(folder / "a_ring.nrrd").ok());
  { std::ofstream(folder / "c_broken.nrrd") << "not a volume"; }
  { std::ofstream(folder / "notes.txt") << "not a tool"; }
  const StationController::ToolLibrary library = StationController::scan_tool_library(folder, 32);
  ASSERT_EQ(library.tools.size(), 2u);
  EXPECT_EQ(library.unreadable, 1);
  EXPECT_EQ(library.tools[0].path.filename(), "a_ring.nrrd");
  EXPECT_EQ(library.tools[1].path.filename(), "b_sphere.nrrd");
  EXPECT_EQ(library.tools[1].dims, sphere_dims);
  for (const StationController::ToolFileEntry& e : library.tools) {
    ASSERT_EQ(e.thumbnail.width, 32);
    ASSERT_EQ(e.thumbnail.rgb.size(), 32u * 32u * 3u);
    // The tool covers part of its picture, not none and not all of it.
    SoftwareView view;
    view.width = view.height = 32;
    const double covered = coverage(e.thumbnail, view);
    EXPECT_GT(covered, 0.05) << e.path;
    EXPECT_LT(covered, 0.95) << e.path;
  }
  EXPECT_TRUE(StationController::scan_tool_library(dir.path() / "none").tools.empty());
}

}  // namespace
}  // namespace sculpt::station
