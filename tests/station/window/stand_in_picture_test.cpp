// What the window draws for dabs waiting for their meshes (stand-ins, app/
// dab_stand_ins.h), through the station's own OpenGL renderer: the clay as
// it was with the stand-ins over it must look like the clay after the dabs,
// adding and carving, mirrored. Without a display the test runs itself
// again under xvfb-run (Mesa's software OpenGL, as in CI).

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../cli/run_sculpt.h"
#include "picture_difference.h"
#include "scratch_dir.h"
#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/station/app/station_loop.h"
#include "sculpt/station/settings/command_codec.h"
#include "sculpt/station/window/gl_snapshot.h"
#include "xvfb_rerun.h"

namespace sculpt::station {
namespace {

constexpr int kBlock = 256;  // clay from 64 to 192 on every axis
constexpr int kPixels = 400;

struct Dabbed {
  core::Mesh before, after;
  core::Tool tool;
  std::vector<DabStandIn> stand_ins;
};

// A stroke of `mode` with a `size`-voxel ball along `path` on the clay,
// mirrored across x = 128: the meshes before and after, and its stand-ins.
Dabbed stroke(core::SculptMode mode, float size, const std::vector<glm::vec3>& path,
              sim::ToolShape shape = sim::ToolShape::kSphere) {
  StationLoop::Options o;
  o.volume_dims = glm::ivec3(kBlock);
  o.clay_margin = 64;
  o.mesh = false;
  StationLoop loop(o);
  DabStandIns board;
  loop.show_stand_ins(&board);
  loop.handle(sim::Command{sim::CommandKind::kTool, choice_of(shape), {size, 0.0f}});
  loop.handle(sim::Command{sim::CommandKind::kMode, choice_of(mode)});
  loop.handle(sim::Command{sim::CommandKind::kMirror, 0, {128.0f}});
  auto pose = [](glm::vec3 p) {
    return sim::Command{sim::CommandKind::kPointer, 0, {p.x, p.y, p.z, 1.0f, 0.0f, 0.0f, 0.0f}};
  };
  sim::Command start = pose(path.front());
  start.kind = sim::CommandKind::kToolPose;
  loop.handle(start);
  Dabbed d;
  d.before = core::marching_cubes(loop.volume());
  loop.handle(sim::Command{sim::CommandKind::kPress});
  for (size_t i = 1; i < path.size(); ++i)
    loop.handle(pose(path[i]));
  loop.handle(sim::Command{sim::CommandKind::kRelease});
  d.after = core::marching_cubes(loop.volume());
  d.tool = loop.tool();
  d.stand_ins = board.showing(0);
  EXPECT_EQ(loop.counters().dabs_stood_in, loop.counters().dabs);
  EXPECT_GE(static_cast<int64_t>(d.stand_ins.size()), loop.counters().dabs);
  return d;
}

void expect_stand_ins_look_sculpted(const Dabbed& d, const char* what) {
  // One framing for the three: the block.
  const GlPictureView view{glm::vec3(kBlock), glm::vec3(0.0f), glm::vec3(kBlock), kPixels, kPixels};
  auto shown = render_mesh_gl(d.before, view, d.tool, d.stand_ins);
  auto sculpted = render_mesh_gl(d.after, view);
  auto old = render_mesh_gl(d.before, view);
  ASSERT_TRUE(shown.ok()) << shown.error().message();
  ASSERT_TRUE(sculpted.ok() && old.ok());
  const sculpt::test::PictureDifference d_shown =
      sculpt::test::picture_difference(shown->rgb, sculpted->rgb);
  const sculpt::test::PictureDifference d_old =
      sculpt::test::picture_difference(old->rgb, sculpted->rgb);
  std::printf(
      "%s (%zu stand-ins): against the sculpted clay mean %.2f, %.2f%% of pixels above 24;"
      " the clay as it was %.2f%%\n",
      what, d.stand_ins.size(), d_shown.mean, 100.0 * d_shown.visible_share,
      100.0 * d_old.visible_share);
  EXPECT_GT(d_old.visible_share, 0.004) << what << ": the dabs show";
  EXPECT_LT(d_shown.visible_share, d_old.visible_share / 5) << what;
  // Measured: 0.08% for both (the rim where kAdd sums the two surfaces; the
  // swept groove's sides between the copies of the tool).
  EXPECT_LT(d_shown.visible_share, 0.004) << what;
  EXPECT_LT(d_shown.mean, 1.0) << what;
}

TEST(StandInPictures, AddingAndCarvingLookLikeTheSculptedClay) {
  if (!display_available()) {
    sculpt::test::ScratchDir dir;
    if (!sculpt::test::rerun_under_xvfb(dir)) GTEST_SKIP() << "no display and no xvfb-run";
    return;
  }
  // The demo's head ball (radius 66), astride the clay's front face.
  expect_stand_ins_look_sculpted(stroke(core::SculptMode::kAdd, 66.0f, {{88.3f, 130.6f, 186.2f}}),
                                 "the demo's head ball added");
  // A groove carved with a ball of radius 12: a stroke of overlapping dabs.
  std::vector<glm::vec3> groove;
  for (float y = 100.0f; y <= 160.0f; y += 1.0f)
    groove.push_back({96.4f, y, 195.3f});
  expect_stand_ins_look_sculpted(stroke(core::SculptMode::kSubtract, 12.0f, groove),
                                 "a groove carved with a ball of radius 12");
  // A cube of 40 voxels (its stand-in marched from its voxels) added on an
  // edge of the clay.
  expect_stand_ins_look_sculpted(
      stroke(core::SculptMode::kAdd, 40.0f, {{84.6f, 190.3f, 186.7f}}, sim::ToolShape::kCube),
      "a 40-voxel cube added");
}

}  // namespace
}  // namespace sculpt::station
