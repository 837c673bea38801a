#include "sculpt/station/app/station_controller.h"

#include <gtest/gtest.h>

#include "scratch_dir.h"
#include "sculpt/core/files/mesh_file.h"
#include "sculpt/core/mesh/mesh_simplify.h"
#include "sculpt/core/volume/material_bounds.h"
#include "sculpt/hal/normalizer/normalizer_config.h"
#include "sculpt/sim/session/session_file.h"
#include "small_block.h"

namespace sculpt::station {
namespace {

constexpr int64_t kMs = 1'000'000;

using test_blocks::small_block;

// A mouse stroke across the clay's top face.
void stroke(StationController& c, int64_t& t, float z) {
  c.pointer_move({20.0f, 52.0f, z}, t += kMs);
  c.pointer_down(t += kMs);
  for (int i = 0; i <= 20; ++i)
    c.pointer_move({20.0f + static_cast<float>(i), 52.0f, z}, t += kMs);
  c.pointer_up(t += kMs);
  c.update_mesh(t);
}

TEST(StationController, TheCameraFramesTheMaterialNotTheBlock) {
  test::ScratchDir dir;
  StationController c(small_block(dir));
  const std::optional<core::Box> clay = core::material_bounds(c.loop().volume());
  ASSERT_TRUE(clay.has_value());
  EXPECT_EQ(c.camera().target(), 0.5f * glm::vec3(clay->lo + clay->hi));
  OrbitCamera whole_block;
  whole_block.frame(glm::vec3(0.0f), glm::vec3(c.loop().volume().dims()));
  EXPECT_LT(c.camera().distance(), 0.8f * whole_block.distance());
  // After orbiting away, the frame action comes back to it.
  c.camera().orbit(1.0f, 0.3f);
  c.camera().pan({40.0f, 10.0f}, 800.0f);
  EXPECT_TRUE(c.perform(Action::kFrameView, 0));
  EXPECT_EQ(c.camera().target(), 0.5f * glm::vec3(clay->lo + clay->hi));
}

// The brush keys choose the ball brushes; a mouse stroke with one is one
// undo step; a recording opens with the brush, the mode under it and the
// accumulate option, so its replay starts as the station was.
TEST(StationController, BrushKeysStrokeAndRecordingsOpenWithTheBrush) {
  test::ScratchDir dir;
  StationController c(small_block(dir));
  int64_t t = 0;
  const std::pair<Action, BallBrush> keys[] = {{Action::kBrushClay, BallBrush::kClay},
                                               {Action::kBrushFlatten, BallBrush::kFlatten},
                                               {Action::kBrushPinch, BallBrush::kPinch},
                                               {Action::kBrushGrab, BallBrush::kGrab},
                                               {Action::kBrushInflate, BallBrush::kInflate}};
  EXPECT_TRUE(c.perform(Action::kToggleAddSubtract, t));  // subtract, kept under the brush
  for (const auto& [action, brush] : keys) {
    EXPECT_TRUE(c.perform(action, t));
    EXPECT_EQ(c.loop().settings().brush, brush);
  }
  EXPECT_TRUE(c.perform(Action::kToggleAccumulate, t));
  EXPECT_TRUE(c.loop().settings().accumulate);
  const uint64_t before = c.loop().volume().content_hash();
  stroke(c, t, 40.0f);
  EXPECT_NE(c.loop().volume().content_hash(), before);
  EXPECT_EQ(c.loop().sculptor().history().undo_depth(), 1u);

  ASSERT_TRUE(c.start_recording(dir.path() / "brush.scs", t += kMs).ok());
  ASSERT_TRUE(c.stop_recording().ok());
  const auto recorded = sim::read_session_file(dir.path() / "brush.scs");
  ASSERT_TRUE(recorded.ok()) << recorded.error().message();
  StationLoop::Options o;
  o.volume_dims = glm::ivec3(64);
  o.mesh = false;
  StationLoop replay(o);
  for (const sim::SessionRecord& r : recorded->records)
    if (r.kind == sim::SessionRecord::Kind::kCommand) replay.handle(r.command);
  EXPECT_EQ(replay.settings().brush, BallBrush::kInflate);
  EXPECT_EQ(replay.settings().mode, core::SculptMode::kSubtract);
  EXPECT_TRUE(replay.settings().accumulate);

  EXPECT_TRUE(c.perform(Action::kSmooth, t));  // a mode leaves the brush
  EXPECT_FALSE(c.loop().settings().brush.has_value());
}

TEST(StationController, SwitchesToolsModesAndSizes) {
  test::ScratchDir dir;
  StationController c(small_block(dir));
  int64_t t = 0;
  EXPECT_TRUE(c.perform(Action::kToolCube, t));
  EXPECT_EQ(c.loop().settings().shape, sim::ToolShape::kCube);
  const float size = c.loop().settings().size_a_vox;
  EXPECT_TRUE(c.perform(Action::kToolBigger, t));
  EXPECT_FLOAT_EQ(c.loop().settings().size_a_vox, size * 1.25f);
  EXPECT_GT(c.loop().tool().density.dims().x, 0);
  EXPECT_TRUE(c.perform(Action::kToggleAddSubtract, t));
  EXPECT_EQ(c.loop().settings().mode, core::SculptMode::kSubtract);
  EXPECT_TRUE(c.perform(Action::kToggleAddSubtract, t));
  EXPECT_EQ(c.loop().settings().mode, core::SculptMode::kAdd);
  EXPECT_TRUE(c.perform(Action::kSmooth, t));
  EXPECT_EQ(c.loop().settings().mode, core::SculptMode::kSmooth);
  for (int i = 0; i < 20; ++i)
    c.perform(Action::kStronger, t);
  EXPECT_FLOAT_EQ(c.loop().settings().strength, 1.0f);
  EXPECT_TRUE(c.perform(Action::kToggleMirror, t));
  ASSERT_TRUE(c.loop().settings().mirror.has_value());
  EXPECT_FLOAT_EQ(c.loop().settings().mirror->centre_vox, 31.5f);
  EXPECT_TRUE(c.perform(Action::kToggleDeviceTarget, t));
  EXPECT_EQ(c.device_target(), DeviceTarget::kCamera);
}

TEST(StationController, MouseSculptsAndUndoRedoRestoreTheVolumeBitForBit) {
  test::ScratchDir dir;
  StationController c(small_block(dir));
  int64_t t = 0;
  const uint64_t before = c.loop().volume().content_hash();
  c.perform(Action::kToggleAddSubtract, t);  // carve
  stroke(c, t, 40.0f);
  const uint64_t after = c.loop().volume().content_hash();
  EXPECT_NE(after, before);
  EXPECT_GT(c.loop().counters().dabs, 5);
  EXPECT_EQ(c.loop().counters().strokes, 1);
  EXPECT_EQ(c.session_latency().count, c.loop().counters().dabs);
  c.undo(t += kMs);
  EXPECT_EQ(c.loop().volume().content_hash(), before);
  EXPECT_EQ(c.status(), "undone");
  c.redo(t += kMs);
  EXPECT_EQ(c.loop().volume().content_hash(), after);
  c.redo(t += kMs);
  EXPECT_EQ(c.status(), "nothing to redo");
}

TEST(StationController, ARecordingReplaysToTheSameVolume) {
  test::ScratchDir dir;
  StationController c(small_block(dir));
  int64_t t = 1000 * kMs;
  ASSERT_TRUE(c.start_recording(dir.path() / "r.scs", t).ok());
  c.set_tool(sim::ToolShape::kSphere, 4.0f, 0.0f, t += kMs);
  stroke(c, t, 40.0f);
  c.set_mode(core::SculptMode::kSubtract, t += kMs);
  c.set_mirror(0, t += kMs);
  stroke(c, t, 30.0f);
  c.undo(t += kMs);
  c.redo(t += kMs);
  c.pointer_move({30.0f, 52.0f, 40.0f}, t += kMs);
  const uint64_t plain = c.loop().volume().content_hash();
  c.hypertexture(t += kMs);
  EXPECT_EQ(c.status(), "hypertexture baked around the tool");
  EXPECT_NE(c.loop().volume().content_hash(), plain);
  c.undo(t += kMs);
  EXPECT_EQ(c.loop().volume().content_hash(), plain);  // a stroke of its own
  c.redo(t += kMs);
  ASSERT_TRUE(c.use_sculpture_as_tool(t += kMs)) << c.status();
  c.set_mode(core::SculptMode::kAdd, t += kMs);
  c.tick(t);
  ASSERT_TRUE(c.stop_recording().ok());

  auto session = sim::read_session_file(dir.path() / "r.scs");
  ASSERT_TRUE(session.ok()) << session.error().message();
  StationLoop replayed(StationLoop::Options{});
  auto r = replay_session(*session, "r.scs", replayed);
  ASSERT_TRUE(r.ok()) << r.error().message();
  EXPECT_EQ(replayed.volume().content_hash(), c.loop().volume().content_hash());
  EXPECT_EQ(replayed.counters().dabs, c.loop().counters().dabs);
  EXPECT_TRUE(replayed.settings().custom_tool);
}

// A recording asked for before the first poll (the window's --record): the
// readers tap reports before the station applies anything, and the device's
// commands come with that poll. A command older than the reports is written
// before them, as the station applied it, not after the reports written at
// once (a session playing as a device replayed to another volume when the
// first poll came late).
TEST(StationController, ReportsTappedBeforeTheFirstPollWaitForTheCommandsBeforeThem) {
  test::ScratchDir dir;
  StationController c(small_block(dir));
  hal::DeviceInfo device;
  device.name = "SpaceMouse Compact";
  c.set_device(device, "");
  const uint8_t bytes[] = {1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  c.raw_report(hal::RawEvent::report(20 * kMs, bytes));
  c.raw_report(hal::RawEvent::report(30 * kMs, bytes));
  ASSERT_TRUE(c.start_recording(dir.path() / "r.scs", 1000 * kMs).ok());
  c.tick(1000 * kMs);  // a flush before the first poll
  hal::InputFrame frame;
  for (int64_t t : {20 * kMs, 30 * kMs}) {
    hal::InputEvent e;
    e.t_ns = t;
    frame.events.push_back(e);
  }
  const sim::Command mode{sim::CommandKind::kMode, 1, {}};
  const std::pair<int64_t, sim::Command> commands[] = {{10 * kMs, mode}};
  c.device_frame(frame, 1001 * kMs, commands);
  ASSERT_TRUE(c.stop_recording().ok());
  auto session = sim::read_session_file(dir.path() / "r.scs");
  ASSERT_TRUE(session.ok()) << session.error().message();
  int command_at = -1, first_report_at = -1;
  for (size_t i = 0; i < session->records.size(); ++i) {
    const sim::SessionRecord& r = session->records[i];
    if (r.kind == sim::SessionRecord::Kind::kEvent && first_report_at < 0)
      first_report_at = static_cast<int>(i);
    if (r.kind == sim::SessionRecord::Kind::kCommand && r.command == mode)
      command_at = static_cast<int>(i);
  }
  ASSERT_GE(command_at, 0);
  ASSERT_GE(first_report_at, 0);
  EXPECT_LT(command_at, first_report_at);
}

// The clutch key is a recorded command, once per change; a recording started
// with it held opens with it held, so the replay re-anchors where the live
// station did when it is let go.
TEST(StationController, ARecordingStartedWithTheClutchHeldOpensClutched) {
  test::ScratchDir dir;
  StationController c(small_block(dir));
  int64_t t = 1000 * kMs;
  c.set_clutch(true, t += kMs);
  ASSERT_TRUE(c.start_recording(dir.path() / "r.scs", t += kMs).ok());
  c.set_clutch(true, t += kMs);  // still held: nothing recorded
  c.set_clutch(false, t += kMs);
  c.tick(t);
  ASSERT_TRUE(c.stop_recording().ok());
  auto session = sim::read_session_file(dir.path() / "r.scs");
  ASSERT_TRUE(session.ok()) << session.error().message();
  std::vector<int> clutch;
  for (const sim::SessionRecord& r : session->records)
    if (r.kind == sim::SessionRecord::Kind::kCommand && r.command.kind == sim::CommandKind::kClutch)
      clutch.push_back(r.command.choice);
  EXPECT_EQ(clutch, (std::vector<int>{1, 0}));
  StationLoop replayed(StationLoop::Options{});
  ASSERT_TRUE(replay_session(*session, "r.scs", replayed).ok());
  EXPECT_FALSE(replayed.clutch_key_held());
  EXPECT_FALSE(c.loop().clutch_key_held());
}

TEST(StationController, SculptureBecomesAToolOnlyWhenThereIsOneOfToolSize) {
  test::ScratchDir dir;
  ControllerOptions o = small_block(dir);
  o.loop.clay_margin = 0;  // an empty block
  StationController empty(o);
  EXPECT_FALSE(empty.use_sculpture_as_tool(0));
  EXPECT_EQ(empty.status(), "no material to make a tool of");

  StationController c(small_block(dir));
  ASSERT_TRUE(c.use_sculpture_as_tool(0));
  EXPECT_TRUE(c.loop().settings().custom_tool);
  // The clay slab spans voxels 12..51 (its density ramp a voxel beyond).
  const glm::ivec3 d = c.loop().tool().density.dims();
  EXPECT_GE(d.x, 40);
  EXPECT_LE(d.x, 44);
  // The size keys scale it (station_tools_test.cpp).
  EXPECT_TRUE(c.perform(Action::kToolBigger, 0)) << c.status();
  EXPECT_EQ(c.loop().settings().tool_scale, 1.25f);

  ControllerOptions big = small_block(dir);
  big.loop.volume_dims = glm::ivec3(128);
  big.loop.clay_margin = 4;
  StationController too_big(big);
  EXPECT_FALSE(too_big.use_sculpture_as_tool(0));
  EXPECT_NE(too_big.status().find("too big"), std::string::npos);
}

TEST(StationController, SavesOpensAndAutosavesTheProject) {
  test::ScratchDir dir;
  StationController c(small_block(dir));
  int64_t t = 0;
  c.tick(t);
  EXPECT_EQ(c.autosaves(), 0);  // nothing changed yet
  stroke(c, t, 40.0f);
  c.tick(t + 100 * kMs);
  c.finish_autosave();
  EXPECT_EQ(c.autosaves(), 0);  // not due yet (1 s)
  c.tick(t + 2000 * kMs);
  c.finish_autosave();
  EXPECT_EQ(c.autosaves(), 1);
  auto autosaved = load_project(c.autosave_path());
  ASSERT_TRUE(autosaved.ok()) << autosaved.error().message();
  EXPECT_EQ(autosaved->volume->content_hash(), c.loop().volume().content_hash());
  c.tick(t + 5000 * kMs);
  c.finish_autosave();
  EXPECT_EQ(c.autosaves(), 1);  // nothing new to save

  const uint64_t sculpted = c.loop().volume().content_hash();
  ASSERT_TRUE(c.perform(Action::kSave, t));
  c.perform(Action::kToolRing, t);
  stroke(c, t, 30.0f);
  EXPECT_NE(c.loop().volume().content_hash(), sculpted);
  ASSERT_TRUE(c.open(c.options().project).ok());
  EXPECT_EQ(c.loop().volume().content_hash(), sculpted);
  EXPECT_EQ(c.loop().settings().shape, sim::ToolShape::kSphere);
  EXPECT_EQ(c.loop().sculptor().history().undo_depth(), 0u);

  ASSERT_TRUE(c.perform(Action::kExportMesh, t));
  EXPECT_GT(std::filesystem::file_size(c.options().mesh_export), 1000u);
  // With a max error: fewer triangles, still closed, the figures in the status.
  auto full = core::read_mesh_file(c.options().mesh_export);
  ASSERT_TRUE(full.ok()) << full.error().message();
  c.options().mesh_export_max_error = 0.5f;
  ASSERT_TRUE(c.perform(Action::kExportMesh, t));
  auto simplified = core::read_mesh_file(c.options().mesh_export);
  ASSERT_TRUE(simplified.ok()) << simplified.error().message();
  EXPECT_LT(simplified->triangles.size(), full->triangles.size() * 3 / 4);
  EXPECT_TRUE(core::check_topology(*simplified).closed());
  EXPECT_LE(core::hausdorff_distance(*full, *simplified), 0.5 + 1e-3);
  EXPECT_NE(c.status().find(" -> "), std::string::npos) << c.status();
  c.options().mesh_export_max_error = 0.0f;
  EXPECT_FALSE(c.open(dir.path() / "missing.sculpt").ok());
  EXPECT_NE(c.status().find("missing.sculpt"), std::string::npos);
  EXPECT_EQ(c.loop().volume().content_hash(), sculpted);  // a failed open changes nothing
}

TEST(StationController, SavesInputSettingsToTheConfigFile) {
  test::ScratchDir dir;
  StationController c(small_block(dir));
  ASSERT_TRUE(c.save_input_settings(2.5f, 0.1f).ok()) << c.status();
  auto config = hal::load_normalizer_config(c.options().normalizer_config_path);
  ASSERT_TRUE(config.ok()) << config.error().message();
  EXPECT_FLOAT_EQ(config->sensitivity[3], 2.5f);
  EXPECT_FLOAT_EQ(config->deadzone[0], 0.1f);
}

TEST(StationController, TheDeviceMovesTheCameraOrTheTool) {
  test::ScratchDir dir;
  StationController c(small_block(dir));
  hal::InputFrame frame;
  hal::InputEvent connected;
  connected.kind = hal::InputKind::kConnected;
  frame.events.push_back(connected);
  hal::InputEvent battery;
  battery.kind = hal::InputKind::kBattery;
  battery.battery_percent = 80;
  frame.events.push_back(battery);
  c.device_frame(frame, 0);
  EXPECT_TRUE(c.device_status().connected);
  EXPECT_EQ(c.device_status().battery_percent, 80);

  c.set_device_target(DeviceTarget::kCamera);
  const float yaw = c.camera().yaw();
  const glm::vec3 tool = c.loop().pose().position;
  for (int i = 1; i <= 10; ++i) {
    hal::InputFrame f;
    hal::InputEvent m;
    m.t_ns = i * 10 * kMs;
    m.axes[hal::kRy] = 0.8f;
    m.integral[hal::kRy] = 0.008 * i;
    f.events.push_back(m);
    c.device_frame(f, m.t_ns);
  }
  EXPECT_NE(c.camera().yaw(), yaw);
  EXPECT_EQ(c.loop().pose().position, tool);
  c.reader_samples(100, 1000 * kMs);
  c.reader_samples(150, 1500 * kMs);  // under a second: not yet
  EXPECT_EQ(c.device_status().report_rate_hz, 0.0);
  c.reader_samples(350, 2000 * kMs);
  EXPECT_DOUBLE_EQ(c.device_status().report_rate_hz, 250.0);
}

}  // namespace
}  // namespace sculpt::station
