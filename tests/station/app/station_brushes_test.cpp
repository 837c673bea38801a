// The ball brushes in the station (StationSettings::brush): a press collects
// the sampler's dabs and the core brush applies to them when it ends.

#include <gtest/gtest.h>

#include <limits>
#include <optional>
#include <string>

#include "sculpt/core/sculpt/clay_brush.h"
#include "sculpt/core/sculpt/flatten_brush.h"
#include "sculpt/core/sculpt/grab_brush.h"
#include "sculpt/core/sculpt/inflate_brush.h"
#include "sculpt/core/sculpt/pinch_brush.h"
#include "sculpt/core/sculpt/smooth_brush.h"
#include "sculpt/hal/stroke/stroke_sampler.h"
#include "sculpt/sim/session/session_file.h"
#include "sculpt/sim/session/session_text.h"
#include "sculpt/sim/synth/bundled_sessions.h"
#include "sculpt/station/app/session_replay.h"
#include "sculpt/station/app/station_loop.h"
#include "sculpt/station/settings/command_codec.h"

namespace sculpt::station {
namespace {

constexpr glm::ivec3 kDims(64);
constexpr int kMargin = 8;  // the slab's top face at z = 55
constexpr float kRadius = 6.0f;
constexpr float kHardness = 0.5f;
constexpr float kStrength = 0.75f;

constexpr BallBrush kBrushes[] = {BallBrush::kClay, BallBrush::kFlatten, BallBrush::kInflate,
                                  BallBrush::kPinch, BallBrush::kGrab};

StationLoop::Options options() {
  StationLoop::Options o;
  o.volume_dims = kDims;
  o.clay_margin = kMargin;
  o.mesh = false;
  return o;
}

// The stroke's tool positions: along x over the slab's top, rising 4 voxels
// (so a grab lifts the material, not only slides it along a flat face).
std::vector<glm::vec3> path() {
  std::vector<glm::vec3> p;
  for (int x = 20; x <= 36; ++x)
    p.emplace_back(static_cast<float>(x), 32.0f, 55.0f + 0.25f * static_cast<float>(x - 20));
  return p;
}

sim::Command pose_command(sim::CommandKind kind, glm::vec3 p) {
  return sim::Command{kind, 0, {p.x, p.y, p.z, 1.0f, 0.0f, 0.0f, 0.0f}};
}

// The commands of one brush stroke along path(), after the settings.
std::vector<sim::Command> stroke_commands(BallBrush brush) {
  const std::vector<glm::vec3> p = path();
  std::vector<sim::Command> c = {
      sim::Command{sim::CommandKind::kTool, choice_of(sim::ToolShape::kSphere), {kRadius, 0.0f}},
      sim::Command{sim::CommandKind::kHardness, 0, {kHardness}},
      sim::Command{sim::CommandKind::kStrength, 0, {kStrength}},
      sim::Command{sim::CommandKind::kMode, choice_of(brush)},
      pose_command(sim::CommandKind::kToolPose, p.front()),
      sim::Command{sim::CommandKind::kPress}};
  for (size_t i = 1; i < p.size(); ++i)
    c.push_back(pose_command(sim::CommandKind::kPointer, p[i]));
  c.push_back(sim::Command{sim::CommandKind::kRelease});
  return c;
}

// The samples the station's sampler places along path() for that tool.
std::vector<core::StrokeSample> sampled_path() {
  hal::StrokeSampler sampler(tool_size_vox(sim::ToolShape::kSphere, kRadius, 0.0f), 0.25f);
  std::vector<hal::Dab> dabs;
  const std::vector<glm::vec3> p = path();
  hal::ToolPose pose;
  pose.position = p.front();
  sampler.begin(pose, dabs);
  for (size_t i = 1; i < p.size(); ++i) {
    pose.position = p[i];
    sampler.add(pose, dabs);
  }
  std::vector<core::StrokeSample> samples;
  for (const hal::Dab& d : dabs)
    samples.push_back({d.position, d.orientation});
  return samples;
}

// The core brush called directly on the same samples: on a fresh block, or
// on `v` as it is.
void core_brush(core::Volume& v, BallBrush brush, const std::vector<core::StrokeSample>& s) {
  core::Sculptor sculptor(v);
  auto with = [](auto o) {
    o.radius_vox = kRadius;
    o.hardness = kHardness;
    o.strength = kStrength;
    return o;
  };
  switch (brush) {
    case BallBrush::kClay:
      core::clay_stroke(v, sculptor, s, with(core::ClayBrushOptions{}));
      break;
    case BallBrush::kFlatten:
      core::flatten_stroke(v, sculptor, s, with(core::FlattenBrushOptions{}));
      break;
    case BallBrush::kInflate:
      core::inflate_stroke(v, sculptor, s, with(core::InflateBrushOptions{}));
      break;
    case BallBrush::kPinch:
      core::pinch_stroke(v, sculptor, s, with(core::PinchBrushOptions{}));
      break;
    case BallBrush::kGrab:
      core::grab_stroke(v, sculptor, s, with(core::GrabBrushOptions{}));
      break;
  }
}
core::Volume core_brush(BallBrush brush) {
  core::Volume v = clay_block(kDims, kMargin);
  core_brush(v, brush, sampled_path());
  return v;
}

int64_t voxels_differing(const core::Volume& a, const core::Volume& b) {
  int64_t n = 0;
  for (int z = 0; z < kDims.z; ++z)
    for (int y = 0; y < kDims.y; ++y)
      for (int x = 0; x < kDims.x; ++x)
        n += a.voxel({x, y, z}) != b.voxel({x, y, z}) ? 1 : 0;
  return n;
}

// Each brush's press changes the block exactly as the core brush does on
// the samples the station's sampler placed, as one undo step that gives the
// block back byte for byte.
TEST(StationBrushes, EachBrushStrokeIsTheCoreBrushAndOneUndoStep) {
  const core::Volume block = clay_block(kDims, kMargin);
  for (const BallBrush brush : kBrushes) {
    SCOPED_TRACE(static_cast<int>(brush));
    StationLoop loop(options());
    for (const sim::Command& c : stroke_commands(brush))
      loop.handle(c);
    EXPECT_EQ(loop.settings().brush, brush);
    const core::Volume expected = core_brush(brush);
    EXPECT_GT(voxels_differing(expected, block), 0) << "the brush changed nothing";
    EXPECT_EQ(voxels_differing(loop.volume(), expected), 0);
    EXPECT_EQ(loop.volume().content_hash(), expected.content_hash());
    EXPECT_EQ(loop.sculptor().history().undo_depth(), 1u);
    loop.handle(sim::Command{sim::CommandKind::kUndo});
    EXPECT_EQ(voxels_differing(loop.volume(), block), 0);
    EXPECT_EQ(loop.volume().content_hash(), block.content_hash());
  }
}

// While the press goes on the brush shows on the path so far (no undo step
// yet); the release leaves exactly what the whole path's brush leaves.
TEST(StationBrushes, ABrushShowsWhileThePressGoesOn) {
  const core::Volume block = clay_block(kDims, kMargin);
  for (const BallBrush brush : kBrushes) {
    SCOPED_TRACE(static_cast<int>(brush));
    StationLoop loop(options());
    std::vector<sim::Command> commands = stroke_commands(brush);
    const sim::Command release = commands.back();
    commands.pop_back();
    for (const sim::Command& c : commands)
      loop.handle(c);
    EXPECT_TRUE(loop.pressed());
    EXPECT_GT(loop.counters().brush_previews, 1);
    EXPECT_NE(loop.volume().content_hash(), block.content_hash()) << "nothing shown mid-press";
    EXPECT_EQ(loop.sculptor().history().undo_depth(), 0u);
    loop.handle(release);
    EXPECT_EQ(loop.volume().content_hash(), core_brush(brush).content_hash());
    EXPECT_EQ(loop.sculptor().history().undo_depth(), 1u);
  }
  // Without previews (`sculpt replay`) the same result.
  StationLoop::Options quiet = options();
  quiet.preview_brushes = false;
  StationLoop loop(quiet);
  for (const sim::Command& c : stroke_commands(BallBrush::kGrab))
    loop.handle(c);
  EXPECT_EQ(loop.counters().brush_previews, 0);
  EXPECT_EQ(loop.volume().content_hash(), core_brush(BallBrush::kGrab).content_hash());
}

// The dabs the previews' cadence leaves for later (the path's tail when the
// hand stops) are shown between polls once the last preview is twice its
// own time behind, and the press still leaves exactly the whole path's brush.
TEST(StationBrushes, ThePathsTailIsShownWhenThePreviewsHaveTimeForIt) {
  StationLoop loop(options());
  const std::vector<sim::Command> commands = stroke_commands(BallBrush::kClay);
  // Up to the first moment past a preview with a dab it does not show.
  size_t next = 0;
  while (next < commands.size() &&
         (loop.counters().brush_previews == 0 || loop.dabs_not_yet_shown() == 0))
    loop.handle(commands[next++]);
  ASSERT_GT(loop.dabs_not_yet_shown(), 0) << "the cadence showed every dab";
  ASSERT_TRUE(loop.pressed());
  const int64_t previews = loop.counters().brush_previews;
  loop.catch_up_brush_preview(0);  // the last preview has just ended: not yet
  EXPECT_EQ(loop.counters().brush_previews, previews);
  EXPECT_GT(loop.dabs_not_yet_shown(), 0);
  loop.catch_up_brush_preview(std::numeric_limits<int64_t>::max() / 2);
  EXPECT_EQ(loop.counters().brush_previews, previews + 1);
  EXPECT_EQ(loop.dabs_not_yet_shown(), 0);
  loop.catch_up_brush_preview(std::numeric_limits<int64_t>::max() / 2);  // nothing new
  EXPECT_EQ(loop.counters().brush_previews, previews + 1);
  // The rest of the press and its release: the whole path's brush.
  while (next < commands.size())
    loop.handle(commands[next++]);
  EXPECT_EQ(loop.dabs_not_yet_shown(), 0);
  EXPECT_EQ(loop.volume().content_hash(), core_brush(BallBrush::kClay).content_hash());
}

// A preview of a grown path, smoothing, inflating or pinching, brushes
// again only what the new samples reach, and shows exactly what the brush
// on the path so far at once leaves: after each pointer report a preview is
// forced and the volume compared with core's brush on the same samples.
TEST(StationBrushes, AGrownPreviewIsTheBrushOnThePathSoFar) {
  // The samples the sampler has placed after each pose of the path.
  hal::StrokeSampler sampler(tool_size_vox(sim::ToolShape::kSphere, kRadius, 0.0f), 0.25f);
  std::vector<hal::Dab> dabs;
  std::vector<size_t> placed;
  const std::vector<glm::vec3> p = path();
  hal::ToolPose pose;
  pose.position = p.front();
  sampler.begin(pose, dabs);
  placed.push_back(dabs.size());
  for (size_t i = 1; i < p.size(); ++i) {
    pose.position = p[i];
    sampler.add(pose, dabs);
    placed.push_back(dabs.size());
  }
  std::vector<core::StrokeSample> samples;
  for (const hal::Dab& d : dabs)
    samples.push_back({d.position, d.orientation});

  // Smooth mode with the ball is the smooth brush; the others are brushes of
  // their own. Clay and flatten fit a plane to the whole path and grab drags
  // what lay under its start, so their previews start again.
  const std::optional<BallBrush> kAll[] = {std::nullopt,     BallBrush::kInflate, BallBrush::kPinch,
                                           BallBrush::kClay, BallBrush::kFlatten, BallBrush::kGrab};
  for (const std::optional<BallBrush> brush : kAll) {
    const bool extends = !brush || brush == BallBrush::kInflate || brush == BallBrush::kPinch;
    const std::string name = brush ? std::to_string(static_cast<int>(*brush)) : "smooth";
    std::vector<sim::Command> commands = stroke_commands(brush.value_or(BallBrush::kClay));
    if (!brush)
      for (sim::Command& c : commands)
        if (c.kind == sim::CommandKind::kMode) c.choice = choice_of(core::SculptMode::kSmooth);
    auto brushed = [&](size_t n) {
      core::Volume v = clay_block(kDims, kMargin);
      const std::vector<core::StrokeSample> first(samples.begin(), samples.begin() + n);
      if (brush) {
        core_brush(v, *brush, first);
      } else {
        core::Sculptor sculptor(v);
        core::SmoothBrushOptions o;
        o.radius_vox = kRadius;
        o.hardness = kHardness;
        o.strength = kStrength;
        core::smooth_stroke(v, sculptor, first, o);
      }
      return v;
    };

    StationLoop loop(options());
    size_t pose_index = 0, compared = 0;
    for (const sim::Command& c : commands) {
      loop.handle(c);
      if (c.kind == sim::CommandKind::kPress) pose_index = 0;
      if (c.kind == sim::CommandKind::kPointer) ++pose_index;
      if (!loop.pressed() || c.kind == sim::CommandKind::kRelease) continue;
      loop.catch_up_brush_preview(std::numeric_limits<int64_t>::max() / 2);
      ASSERT_EQ(loop.dabs_not_yet_shown(), 0) << name;
      const size_t n = placed[pose_index];
      if (n == 0) continue;
      ASSERT_EQ(voxels_differing(loop.volume(), brushed(n)), 0) << name << ", " << n << " samples";
      ++compared;
    }
    EXPECT_EQ(compared, p.size()) << name;
    // The first preview brushes the path; every later one extends it (or
    // brushes the path again).
    EXPECT_GE(loop.counters().brush_previews, 4) << name;
    EXPECT_EQ(loop.counters().brush_previews_extended,
              extends ? loop.counters().brush_previews - 1 : 0)
        << name;
    // The release: the whole path's brush, one undo step.
    EXPECT_EQ(loop.volume().content_hash(), brushed(samples.size()).content_hash()) << name;
    EXPECT_EQ(loop.sculptor().history().undo_depth(), 1u) << name;
  }
}

// Smooth mode with the ball tool is core's smooth brush along the path (one
// undo step, shown while the press goes on).
TEST(StationBrushes, SmoothModeWithTheBallIsTheSmoothBrush) {
  const core::Volume block = clay_block(kDims, kMargin);
  std::vector<sim::Command> commands = stroke_commands(BallBrush::kClay);
  // The same stroke, in smooth mode instead of the clay brush.
  for (sim::Command& c : commands)
    if (c.kind == sim::CommandKind::kMode) c.choice = choice_of(core::SculptMode::kSmooth);
  StationLoop loop(options());
  for (const sim::Command& c : commands)
    loop.handle(c);
  EXPECT_FALSE(loop.settings().brush.has_value());
  EXPECT_EQ(loop.settings().mode, core::SculptMode::kSmooth);
  EXPECT_GT(loop.counters().brush_previews, 0);
  core::Volume expected = clay_block(kDims, kMargin);
  {
    core::Sculptor sculptor(expected);
    core::SmoothBrushOptions o;
    o.radius_vox = kRadius;
    o.hardness = kHardness;
    o.strength = kStrength;
    core::smooth_stroke(expected, sculptor, sampled_path(), o);
  }
  EXPECT_GT(voxels_differing(expected, block), 0) << "the smoothing changed nothing";
  EXPECT_EQ(loop.volume().content_hash(), expected.content_hash());
  EXPECT_EQ(loop.sculptor().history().undo_depth(), 1u);
}

// Choosing a mode leaves the brush; choosing a brush keeps the mode for
// later; the device's add/subtract button leaves the brush too.
TEST(StationBrushes, AModeLeavesTheBrushAndABrushKeepsTheMode) {
  StationLoop loop(options());
  loop.handle(sim::Command{sim::CommandKind::kMode, choice_of(core::SculptMode::kSubtract)});
  loop.handle(sim::Command{sim::CommandKind::kMode, choice_of(BallBrush::kPinch)});
  EXPECT_EQ(loop.settings().brush, BallBrush::kPinch);
  EXPECT_EQ(loop.settings().mode, core::SculptMode::kSubtract);
  loop.handle(sim::Command{sim::CommandKind::kMode, choice_of(core::SculptMode::kAdd)});
  EXPECT_FALSE(loop.settings().brush.has_value());
  loop.handle(sim::Command{sim::CommandKind::kMode, choice_of(BallBrush::kGrab)});
  hal::InputEvent button;
  button.kind = hal::InputKind::kButton;
  button.button = 1;
  button.pressed = true;
  loop.handle(button);
  EXPECT_FALSE(loop.settings().brush.has_value());
  EXPECT_EQ(loop.settings().mode, core::SculptMode::kSubtract);
}

// A session of brush strokes, written and read back in both forms, replays
// to the volume the live loop made, bit for bit.
TEST(StationBrushes, ARecordedBrushSessionReplaysBitForBit) {
  sim::Session s = sim::short_session();
  s.records.clear();
  int64_t t = 0;
  auto add = [&](const sim::Command& c) {
    s.records.push_back(sim::SessionRecord::of(t += 1000, c));
  };
  add(sim::Command{sim::CommandKind::kVolume,
                   sim::kVolumeClay,
                   {static_cast<float>(kDims.x), static_cast<float>(kDims.y),
                    static_cast<float>(kDims.z), static_cast<float>(kMargin)}});
  add(sim::Command{sim::CommandKind::kAccumulate, 1});
  for (const BallBrush brush : kBrushes)
    for (const sim::Command& c : stroke_commands(brush))
      add(c);

  StationLoop live(options());
  for (const sim::SessionRecord& r : s.records)
    live.handle(r.command);
  EXPECT_TRUE(live.settings().accumulate);
  EXPECT_EQ(live.sculptor().history().undo_depth(), 5u);

  const auto binary = sim::parse_session_bytes(sim::serialize_session(s), "brushes.scs");
  ASSERT_TRUE(binary.ok()) << binary.error().message();
  const auto text = sim::session_from_text(sim::session_to_text(s), "brushes.jsonl");
  ASSERT_TRUE(text.ok()) << text.error().message();
  EXPECT_NE(sim::session_to_text(s).find(R"("inflate")"), std::string::npos);
  for (const sim::Session* read : {&*binary, &*text}) {
    StationLoop loop(StationLoop::Options{});
    ReplayOptions o;
    o.fast = true;
    const auto r = replay_session(*read, "brushes", loop, o);
    ASSERT_TRUE(r.ok()) << r.error().message();
    EXPECT_EQ(loop.volume().content_hash(), live.volume().content_hash());
    EXPECT_EQ(voxels_differing(loop.volume(), live.volume()), 0);
  }
}

// Accumulate on: a stroke crossing itself builds up where it crosses; off,
// the strength applies once per voxel (the swept stroke's own option, as
// the session command and the setting carry it).
TEST(StationBrushes, AccumulateBuildsUpWhereAStrokeCrossesItself) {
  auto there_and_back = [](bool accumulate) {
    StationLoop loop(options());
    loop.handle(sim::Command{sim::CommandKind::kAccumulate, static_cast<uint8_t>(accumulate)});
    loop.handle(sim::Command{sim::CommandKind::kStrength, 0, {0.25f}});
    loop.handle(pose_command(sim::CommandKind::kToolPose, {20.0f, 32.0f, 56.0f}));
    loop.handle(sim::Command{sim::CommandKind::kPress});
    for (int x = 21; x <= 40; ++x)
      loop.handle(pose_command(sim::CommandKind::kPointer, {static_cast<float>(x), 32.0f, 56.0f}));
    for (int x = 39; x >= 20; --x)
      loop.handle(pose_command(sim::CommandKind::kPointer, {static_cast<float>(x), 32.0f, 56.0f}));
    loop.handle(sim::Command{sim::CommandKind::kRelease});
    EXPECT_EQ(loop.settings().accumulate, accumulate);
    EXPECT_EQ(loop.sculptor().history().undo_depth(), 1u);
    int64_t sum = 0;
    for (int z = 48; z < 64; ++z)
      sum += loop.volume().voxel({30, 32, z});
    return sum;
  };
  EXPECT_GT(there_and_back(true), there_and_back(false));
}

// A click without a drag (one sample: grab has nothing to drag) and strokes
// far outside the block (a session may place the tool up to 2^20 voxels
// out) run safely: the brushes clip to the block.
TEST(StationBrushes, AClickAndAStrokeOutsideTheBlockAreSafe) {
  const core::Volume block = clay_block(kDims, kMargin);
  for (const BallBrush brush : kBrushes) {
    SCOPED_TRACE(static_cast<int>(brush));
    StationLoop loop(options());
    loop.handle(sim::Command{sim::CommandKind::kMode, choice_of(brush)});
    loop.handle(pose_command(sim::CommandKind::kToolPose, {32.0f, 32.0f, 56.0f}));
    loop.handle(sim::Command{sim::CommandKind::kPress});
    loop.handle(sim::Command{sim::CommandKind::kRelease});
    if (brush == BallBrush::kGrab) {
      EXPECT_EQ(voxels_differing(loop.volume(), block), 0);
    }
    loop.handle(pose_command(sim::CommandKind::kToolPose, {-1.0e6f, 32.0f, 56.0f}));
    loop.handle(sim::Command{sim::CommandKind::kPress});
    loop.handle(pose_command(sim::CommandKind::kPointer, {-1.0e6f + 10.0f, 40.0f, 56.0f}));
    loop.handle(sim::Command{sim::CommandKind::kRelease});
    loop.handle(pose_command(sim::CommandKind::kToolPose, {1.0e6f, 1.0e6f, 1.0e6f}));
    loop.handle(sim::Command{sim::CommandKind::kPress});
    loop.handle(pose_command(sim::CommandKind::kPointer, {1.0e6f, 1.0e6f, 1.0e6f - 30.0f}));
    loop.handle(sim::Command{sim::CommandKind::kRelease});
    EXPECT_EQ(loop.volume().dims(), kDims);
  }
}

// With a mirror plane the brush runs along the path and then along its
// mirror image, as the core brush called twice does, and one undo takes both
// sides back byte for byte.
TEST(StationBrushes, AMirroredBrushStrokeIsBothSidesInOneUndoStep) {
  const core::Volume block = clay_block(kDims, kMargin);
  constexpr float kPlane = 30.5f;  // across x, the path crossing it
  for (const BallBrush brush : kBrushes) {
    SCOPED_TRACE(static_cast<int>(brush));
    StationLoop loop(options());
    loop.handle(sim::Command{sim::CommandKind::kMirror, 0, {kPlane}});
    for (const sim::Command& c : stroke_commands(brush))
      loop.handle(c);
    core::Volume expected = clay_block(kDims, kMargin);
    std::vector<core::StrokeSample> samples = sampled_path();
    core_brush(expected, brush, samples);
    for (core::StrokeSample& m : samples)
      m.position_vox.x = 2.0f * kPlane - m.position_vox.x;
    core_brush(expected, brush, samples);
    EXPECT_EQ(voxels_differing(loop.volume(), expected), 0);
    EXPECT_NE(voxels_differing(expected, core_brush(brush)), 0) << "the mirror did nothing";
    EXPECT_EQ(loop.sculptor().history().undo_depth(), 1u);
    loop.handle(sim::Command{sim::CommandKind::kUndo});
    EXPECT_EQ(voxels_differing(loop.volume(), block), 0);
  }
}

}  // namespace
}  // namespace sculpt::station
