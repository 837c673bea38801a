// The NURBS sheet in the station: what the panel's sheet section, its
// shortcuts and the mouse do, and that a recording replays it bit for bit.

#include <gtest/gtest.h>

#include "scratch_dir.h"
#include "sculpt/core/nurbs/nurbs_json.h"
#include "sculpt/core/nurbs/point_inversion.h"
#include "sculpt/sim/session/session_file.h"
#include "sculpt/station/app/session_start.h"
#include "sculpt/station/app/station_controller.h"

namespace sculpt::station {
namespace {

namespace fs = std::filesystem;
constexpr int64_t kMs = 1'000'000;

ControllerOptions small_block(const test::ScratchDir& dir) {
  ControllerOptions o;
  o.loop.volume_dims = glm::ivec3(64);
  o.project = dir.path() / "p.sculpt";
  o.recording = dir.path() / "r.scs";
  o.sheet_export = dir.path() / "sheet";
  o.autosave_seconds = 0;
  o.normalizer_config_path = (dir.path() / "cfg" / "input.conf").string();
  return o;
}

// The camera looks along -z by default: a new sheet faces it.
void new_sheet_at(StationController& c, int64_t& t, glm::vec3 tool) {
  c.pointer_move(tool, t += kMs);
  c.new_sheet(t += kMs);
}

// Presses at `from`, moves `by` in `steps`, lets go.
void drag(StationController& c, int64_t& t, glm::vec3 from, glm::vec3 by, int steps = 20) {
  c.pointer_move(from, t += kMs);
  c.pointer_down(t += kMs);
  for (int i = 1; i <= steps; ++i)
    c.pointer_move(from + by * (static_cast<float>(i) / static_cast<float>(steps)), t += kMs);
  c.pointer_up(t += kMs);
}

TEST(StationSheet, KeysTurnAndTiltTheTool) {
  test::ScratchDir dir;
  StationController c(small_block(dir));
  int64_t t = 0;
  const glm::quat start = c.loop().pose().orientation;
  for (int i = 0; i < 6; ++i)
    ASSERT_TRUE(c.perform(Action::kTurnToolLeft, t += kMs));  // 6 x 15 = 90 degrees
  const glm::quat q = c.loop().pose().orientation;
  EXPECT_NEAR(std::abs(glm::dot(q, start)), std::cos(0.25 * 3.14159265), 1e-5);
  ASSERT_TRUE(c.perform(Action::kTiltToolUp, t += kMs));
  EXPECT_LT(std::abs(glm::dot(c.loop().pose().orientation, q)), 0.9999f);
}

TEST(StationSheet, PressesDragTheSheetNotTheMaterialAndUndoFollowsTheMode) {
  test::ScratchDir dir;
  StationController c(small_block(dir));
  int64_t t = 0;
  new_sheet_at(c, t, {32.0f, 32.0f, 30.0f});
  ASSERT_TRUE(c.loop().sheet().has_sheet());
  EXPECT_TRUE(c.loop().settings().sheet_editing);
  const core::nurbs::NurbsSurface placed = c.loop().sheet().surface();
  EXPECT_NEAR(core::nurbs::evaluate(placed, 0.5, 0.5).z, 30.0, 1e-9);
  const uint64_t empty = c.loop().volume().content_hash();

  drag(c, t, {32.0f, 32.0f, 30.0f}, {0.0f, 0.0f, 10.0f});
  EXPECT_EQ(c.loop().counters().sheet_grabs, 1);
  EXPECT_EQ(c.loop().counters().dabs, 0) << "a sheet drag does not sculpt";
  EXPECT_EQ(c.loop().volume().content_hash(), empty);
  const core::nurbs::NurbsSurface dragged = c.loop().sheet().surface();
  const core::nurbs::SurfacePoint grabbed = core::nurbs::closest_point(placed, {32.0, 32.0, 30.0});
  EXPECT_LT(glm::length(core::nurbs::evaluate(dragged, grabbed.u, grabbed.v) -
                        glm::dvec3(32.0, 32.0, 40.0)),
            1e-9);

  // Missing the sheet: a press far from it grabs nothing and says why.
  drag(c, t, {5.0f, 5.0f, 60.0f}, {0.0f, 0.0f, -5.0f});
  EXPECT_EQ(c.loop().counters().sheet_misses, 1);
  EXPECT_NE(c.loop().sheet_problem().find("move within"), std::string::npos);

  c.undo(t += kMs);  // sheet editing: the sheet's drag
  EXPECT_EQ(c.loop().sheet().surface().points, placed.points);
  c.redo(t += kMs);
  EXPECT_EQ(c.loop().sheet().surface().points, dragged.points);

  // Its shell into the material, then Undo (now sculpting) takes it back.
  c.set_sheet_thickness(4.0f);
  ASSERT_TRUE(c.sheet_into_material(true, t += kMs)) << c.status();
  EXPECT_FALSE(c.loop().settings().sheet_editing);
  const uint64_t added = c.loop().volume().content_hash();
  EXPECT_NE(added, empty);
  const core::DenseGrid<uint8_t> d = c.loop().volume().to_dense();
  EXPECT_GT(d.at(32, 32, 40), 127) << "the shell lies on the dragged sheet";
  EXPECT_LT(d.at(32, 32, 30), 128) << "not where the sheet was";
  c.undo(t += kMs);
  EXPECT_EQ(c.loop().volume().content_hash(), empty);
  c.redo(t += kMs);
  EXPECT_EQ(c.loop().volume().content_hash(), added);
  ASSERT_TRUE(c.sheet_into_material(false, t += kMs));
  EXPECT_LT(c.loop().volume().to_dense().at(32, 32, 40), 128) << "cut away again";
}

TEST(StationSheet, TheSheetBecomesATool) {
  test::ScratchDir dir;
  StationController c(small_block(dir));
  int64_t t = 0;
  new_sheet_at(c, t, {32.0f, 32.0f, 30.0f});
  c.set_sheet_thickness(3.0f);
  ASSERT_TRUE(c.sheet_as_tool(t += kMs)) << c.status();
  EXPECT_TRUE(c.loop().settings().custom_tool);
  EXPECT_FALSE(c.loop().settings().sheet_editing);
  const glm::ivec3 dims = c.loop().tool().density.dims();
  EXPECT_GE(dims.x, 32);  // the sheet is 32 voxels square (half the block)
  EXPECT_LE(dims.z, 8);   // and a 3-voxel shell thick
  // A sheet bigger than a tool may be is refused with the reason.
  StationController big(small_block(dir));
  big.command(sim::Command{sim::CommandKind::kVolume, sim::kVolumeFill, {512, 512, 64, 0}}, t);
  new_sheet_at(big, t, {256.0f, 256.0f, 30.0f});
  EXPECT_FALSE(big.sheet_as_tool(t += kMs));
  EXPECT_NE(big.status().find("too big for a tool"), std::string::npos) << big.status();
}

TEST(StationSheet, ExportsTheSheetAsNurbsAndAsAMesh) {
  test::ScratchDir dir;
  StationController c(small_block(dir));
  int64_t t = 0;
  EXPECT_FALSE(c.export_sheet(dir.path() / "none").ok());
  new_sheet_at(c, t, {32.0f, 32.0f, 30.0f});
  drag(c, t, {32.0f, 32.0f, 30.0f}, {4.0f, 0.0f, 6.0f});
  ASSERT_TRUE(c.export_sheet(dir.path() / "sheet").ok()) << c.status();
  auto back = core::nurbs::read_surface_json(dir.path() / "sheet.json");
  ASSERT_TRUE(back.ok()) << back.error().message();
  EXPECT_EQ(back->points, c.loop().sheet().surface().points);  // exact round trip
  EXPECT_TRUE(std::filesystem::file_size(dir.path() / "sheet.obj") > 0);
  EXPECT_TRUE(std::filesystem::file_size(dir.path() / "sheet.ply") > 0);
}

TEST(StationSheet, TheProjectKeepsTheSheetAndItsSettings) {
  test::ScratchDir dir;
  StationController c(small_block(dir));
  int64_t t = 0;
  new_sheet_at(c, t, {32.0f, 32.0f, 30.0f});
  c.set_sheet_influence(SheetInfluence::kZone, 0.15f, t += kMs);
  drag(c, t, {32.0f, 32.0f, 30.0f}, {2.0f, 1.0f, 7.0f});
  ASSERT_TRUE(c.save(dir.path() / "s.sculpt").ok()) << c.status();

  StationController d(small_block(dir));
  ASSERT_TRUE(d.open(dir.path() / "s.sculpt").ok()) << d.status();
  ASSERT_TRUE(d.loop().sheet().has_sheet());
  EXPECT_EQ(d.loop().sheet().surface().points, c.loop().sheet().surface().points);
  EXPECT_EQ(d.loop().sheet().surface().knots_v, c.loop().sheet().surface().knots_v);
  EXPECT_TRUE(d.loop().settings().sheet_editing);
  EXPECT_EQ(d.loop().settings().sheet_drag.influence, SheetInfluence::kZone);
  EXPECT_FLOAT_EQ(static_cast<float>(d.loop().settings().sheet_drag.radius), 0.15f);
  t = 0;
  d.undo(t += kMs);  // an opened project starts with no history
  EXPECT_EQ(d.status(), "nothing to undo");
  // And a project without a sheet opens without one.
  d.remove_sheet(t += kMs);
  ASSERT_TRUE(d.save(dir.path() / "none.sculpt").ok());
  ASSERT_TRUE(c.open(dir.path() / "none.sculpt").ok());
  EXPECT_FALSE(c.loop().sheet().has_sheet());
}

// A recording started on a sculpture (and a sheet) replays onto it, both
// through the library and through `sculpt replay`'s loading path.
TEST(StationSheet, ARecordingStartedOnASculptureReplaysOntoIt) {
  test::ScratchDir dir;
  StationController c(small_block(dir));
  int64_t t = 1000 * kMs;
  new_sheet_at(c, t, {32.0f, 32.0f, 30.0f});
  drag(c, t, {32.0f, 32.0f, 30.0f}, {0.0f, 0.0f, 6.0f});
  ASSERT_TRUE(c.sheet_into_material(true, t += kMs));  // material before the recording
  const fs::path rec = dir.path() / "later.scs";
  ASSERT_TRUE(c.start_recording(rec, t += kMs).ok()) << c.status();
  EXPECT_NE(c.status().find("starting from this sculpture"), std::string::npos) << c.status();
  ASSERT_TRUE(fs::exists(session_start_path(rec)));
  c.set_sheet_editing(true, t += kMs);
  drag(c, t, {20.0f, 20.0f, 30.0f}, {0.0f, 0.0f, -6.0f});
  c.set_sheet_editing(false, t += kMs);
  c.set_tool(sim::ToolShape::kSphere, 3.0f, 0.0f, t += kMs);
  drag(c, t, {10.0f, 32.0f, 36.0f}, {40.0f, 0.0f, 0.0f});  // carves through the shell
  c.tick(t);
  ASSERT_TRUE(c.stop_recording().ok());

  auto session = sim::read_session_file(rec);
  ASSERT_TRUE(session.ok()) << session.error().message();
  StationLoop replayed(StationLoop::Options{});
  auto started = restore_session_start(rec, replayed);
  ASSERT_TRUE(started.ok()) << started.error().message();
  EXPECT_TRUE(*started);
  ASSERT_TRUE(replay_session(*session, "later.scs", replayed).ok());
  EXPECT_EQ(replayed.volume().content_hash(), c.loop().volume().content_hash());
  EXPECT_EQ(replayed.sheet().surface().points, c.loop().sheet().surface().points);

  // A recording from a fresh station removes a stale start of that name.
  StationController fresh(small_block(dir));
  ASSERT_TRUE(fresh.start_recording(rec, t += kMs).ok());
  ASSERT_TRUE(fresh.stop_recording().ok());
  EXPECT_FALSE(fs::exists(session_start_path(rec)));
  StationLoop none(StationLoop::Options{});
  EXPECT_FALSE(*restore_session_start(rec, none));
}

TEST(StationSheet, ARecordingReplaysTheSheetBitForBit) {
  test::ScratchDir dir;
  StationController c(small_block(dir));
  int64_t t = 1000 * kMs;
  ASSERT_TRUE(c.start_recording(dir.path() / "r.scs", t).ok());
  new_sheet_at(c, t, {32.0f, 32.0f, 30.0f});
  c.set_sheet_influence(SheetInfluence::kZone, 0.2f, t += kMs);
  drag(c, t, {30.0f, 34.0f, 30.0f}, {3.0f, -2.0f, 12.0f}, 40);
  c.set_sheet_influence(SheetInfluence::kGaussian, 2.0f, t += kMs);
  drag(c, t, {20.0f, 20.0f, 30.0f}, {0.0f, 0.0f, -8.0f}, 10);
  ASSERT_TRUE(c.sheet_into_material(true, t += kMs));
  c.tick(t);
  ASSERT_TRUE(c.stop_recording().ok());

  auto session = sim::read_session_file(dir.path() / "r.scs");
  ASSERT_TRUE(session.ok()) << session.error().message();
  StationLoop replayed(StationLoop::Options{});
  ASSERT_TRUE(replay_session(*session, "r.scs", replayed).ok());
  ASSERT_TRUE(replayed.sheet().has_sheet());
  EXPECT_EQ(replayed.sheet().surface().points, c.loop().sheet().surface().points);
  EXPECT_EQ(replayed.sheet().surface().knots_u, c.loop().sheet().surface().knots_u);
  EXPECT_EQ(replayed.volume().content_hash(), c.loop().volume().content_hash());
  EXPECT_EQ(replayed.counters().sheet_grabs, 2);
}

}  // namespace
}  // namespace sculpt::station
