#include "sculpt/sim/session/command_limits.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "sculpt/sim/session/session_file.h"
#include "sculpt/sim/session/session_text.h"

namespace sculpt::sim {
namespace {

Command command(CommandKind kind, uint8_t choice, std::initializer_list<float> values) {
  Command c{kind, choice};
  int i = 0;
  for (const float v : values)
    c.values[i++] = v;
  return c;
}

Session with(const Command& c) {
  Session s;
  s.header.device.backend = "sim";
  s.records.push_back(SessionRecord::of(1000, command(CommandKind::kPress, 0, {})));
  s.records.push_back(SessionRecord::of(2000, c));
  return s;
}

TEST(CommandLimits, CommandsTheStationWritesPass) {
  EXPECT_FALSE(command_problem(command(CommandKind::kTool, 4, {12.5f, 3.0f})));
  EXPECT_FALSE(command_problem(command(CommandKind::kMode, 4, {})));
  EXPECT_FALSE(command_problem(command(CommandKind::kMirror, kMirrorOff, {0.0f})));
  EXPECT_FALSE(command_problem(command(CommandKind::kMirror, 2, {127.5f})));
  EXPECT_FALSE(command_problem(command(CommandKind::kVolume, kVolumeClay, {256, 256, 256, 64})));
  EXPECT_FALSE(command_problem(command(CommandKind::kVolume, kVolumeFill, {65536, 65536, 1, 0})));
  EXPECT_FALSE(command_problem(command(CommandKind::kToolPose, 0, {10, -5, 3, 1, 0, 0, 0})));
  EXPECT_FALSE(command_problem(command(CommandKind::kSheet, 0, {64, 64, 64, 100, 8, 2})));
  EXPECT_FALSE(command_problem(command(CommandKind::kTouch, 1, {})));
  EXPECT_FALSE(command_problem(command(CommandKind::kClutch, 1, {})));
  EXPECT_FALSE(command_problem(command(CommandKind::kTracker, 0, {0.25f, 0.5f, 0.5f, 0.5f, 0.5f})));
  EXPECT_FALSE(command_problem(command(CommandKind::kHardness, 0, {0.0f})));
  EXPECT_FALSE(command_problem(command(CommandKind::kHardness, 0, {1.0f})));
  EXPECT_FALSE(command_problem(command(CommandKind::kMode, 5, {})));  // clay
  EXPECT_FALSE(command_problem(command(CommandKind::kMode, 9, {})));  // grab
  EXPECT_FALSE(command_problem(command(CommandKind::kAccumulate, 0, {})));
  EXPECT_FALSE(command_problem(command(CommandKind::kAccumulate, 1, {})));
  EXPECT_FALSE(command_problem(command(CommandKind::kToolScale, 0, {0.125f})));
  EXPECT_FALSE(command_problem(command(CommandKind::kToolScale, 0, {8.0f})));
  EXPECT_FALSE(command_problem(command(CommandKind::kMorphology, kMorphologyOffset, {-64.0f})));
  EXPECT_FALSE(command_problem(command(CommandKind::kMorphology, kMorphologyClose, {0.5f})));
}

TEST(CommandLimits, EachOutOfRangeFieldIsNamed) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const struct {
    Command c;
    const char* says;
  } cases[] = {
      {command(CommandKind::kTool, 200, {4, 4}), "tool shape 200 unknown"},
      {command(CommandKind::kMode, 10, {}), "sculpt mode 10 unknown"},
      {command(CommandKind::kAccumulate, 2, {}), "accumulate 2 unknown"},
      {command(CommandKind::kMirror, 3, {0}), "mirror axis 3 unknown"},
      {command(CommandKind::kSheet, 6, {0, 0, 0, 0, 0, 0}), "sheet action 6 unknown"},
      {command(CommandKind::kSheet, 0, {0, 0, 0, 10, 8, 7}), "sheet axis 7"},
      {command(CommandKind::kPress, 9, {}), "choice 9 unknown"},
      {command(CommandKind::kTouch, 2, {}), "touch 2 unknown"},
      {command(CommandKind::kClutch, 2, {}), "clutch 2 unknown"},
      {command(CommandKind::kTracker, 0, {0, 1, 0, 0, 0}), "tracker scale 0 is outside"},
      {command(CommandKind::kTracker, 0, {2000, 1, 0, 0, 0}), "tracker scale 2000 is outside"},
      {command(CommandKind::kTracker, 0, {1, 2, 0, 0, 0}), "not a unit quaternion"},
      {command(CommandKind::kTracker, 0, {1, 0, 0, 0, 0}), "not a unit quaternion"},
      {command(CommandKind::kTracker, 0, {1, nan, 0, 0, 0}), "value 1 is not a finite number"},
      {command(CommandKind::kTool, 0, {500, 4}), "tool size 500 is outside (0, 256]"},
      {command(CommandKind::kTool, 0, {nan, 4}), "value 0 is not a finite number"},
      {command(CommandKind::kStrength, 0, {inf}), "value 0 is not a finite number"},
      {command(CommandKind::kStrength, 0, {1.5f}), "strength 1.5 is outside [0, 1]"},
      {command(CommandKind::kHardness, 0, {-0.5f}), "hardness -0.5 is outside [0, 1]"},
      {command(CommandKind::kHardness, 0, {nan}), "value 0 is not a finite number"},
      {command(CommandKind::kHardness, 3, {0.5f}), "choice 3 unknown"},
      {command(CommandKind::kSpacing, 0, {0}), "spacing 0 is outside (0, 16]"},
      {command(CommandKind::kVolume, 0, {1 << 20, 1 << 20, 1 << 20, 0}), "over the limit of 2^32"},
      {command(CommandKind::kVolume, 0, {64.5f, 64, 64, 0}), "volume side 64.5"},
      {command(CommandKind::kVolume, 0, {64, 64, 64, 300}), "fill density 300"},
      {command(CommandKind::kToolPose, 0, {1e30f, 0, 0, 1, 0, 0, 0}), "coordinate 1e+30 is beyond"},
      {command(CommandKind::kPointer, 0, {0, 0, 0, 0, 0, 0, 0}), "orientation is not a rotation"},
      {command(CommandKind::kToolFromRegion, 0, {0, 0, 0, 2000, 10, 10}), "region side 2000"},
      {command(CommandKind::kToolScale, 0, {0.1f}), "tool scale 0.1 is outside [0.125, 8]"},
      {command(CommandKind::kToolScale, 0, {9.0f}), "tool scale 9 is outside [0.125, 8]"},
      {command(CommandKind::kToolScale, 0, {nan}), "value 0 is not a finite number"},
      {command(CommandKind::kToolScale, 1, {2.0f}), "choice 1 unknown"},
      {command(CommandKind::kMorphology, 2, {1.0f}), "morphology 2 unknown"},
      {command(CommandKind::kMorphology, kMorphologyOffset, {65.0f}),
       "offset 65 is outside [-64, 64] voxels"},
      {command(CommandKind::kMorphology, kMorphologyClose, {0.0f}),
       "closing radius 0 is outside (0, 64] voxels"},
  };
  for (const auto& [c, says] : cases) {
    const auto why = command_problem(c);
    ASSERT_TRUE(why) << says;
    EXPECT_NE(why->find(says), std::string::npos) << *why;
  }
}

// The reproducer of the crash: a command record whose CRC holds but whose
// choice indexes past the name tables. The binary reader stops there with a
// warning naming the record; the text converter never sees it.
TEST(CommandLimits, ABinarySessionStopsAtTheBadCommandWithAWarning) {
  const std::vector<uint8_t> bytes =
      serialize_session(with(command(CommandKind::kTool, 200, {4, 4})));
  SessionReadInfo info;
  const auto r = parse_session_bytes(bytes, "bad.scs", &info);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->records.size(), 1u);
  EXPECT_NE(info.warning.find("bad.scs: record 2: tool command: tool shape 200 unknown"),
            std::string::npos)
      << info.warning;
  EXPECT_NE(session_to_text(*r).find("press"), std::string::npos);
}

// A brush id past the last and an accumulate that is neither on nor off:
// the binary reader stops at the record with one warning naming it, the
// text reader refuses the line.
TEST(CommandLimits, BadBrushAndAccumulateValuesAreRefusedByBothReaders) {
  const struct {
    Command c;
    const char* binary_says;
  } cases[] = {
      {command(CommandKind::kMode, kSculptModeCount, {}),
       "bad.scs: record 2: mode command: sculpt mode 10 unknown"},
      {command(CommandKind::kAccumulate, 7, {}),
       "bad.scs: record 2: accumulate command: accumulate 7 unknown"},
  };
  for (const auto& [c, says] : cases) {
    SessionReadInfo info;
    const auto r = parse_session_bytes(serialize_session(with(c)), "bad.scs", &info);
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r->records.size(), 1u);
    EXPECT_NE(info.warning.find(says), std::string::npos) << info.warning;
  }
  const std::string head = session_to_text(with(command(CommandKind::kPress, 0, {})));
  const auto mode = session_from_text(
      head + "{\"t\": 3000, \"cmd\": \"mode\", \"mode\": \"smudge\"}\n", "bad.jsonl");
  ASSERT_FALSE(mode.ok());
  EXPECT_NE(mode.error().message().find("bad.jsonl:4: "), std::string::npos)
      << mode.error().message();
  EXPECT_NE(mode.error().message().find("smudge"), std::string::npos) << mode.error().message();
  const auto accumulate =
      session_from_text(head + "{\"t\": 3000, \"cmd\": \"accumulate\", \"on\": 2}\n", "bad.jsonl");
  ASSERT_FALSE(accumulate.ok());
  EXPECT_NE(accumulate.error().message().find("bad.jsonl:4: "), std::string::npos)
      << accumulate.error().message();
  EXPECT_NE(accumulate.error().message().find("on: expected true or false"), std::string::npos)
      << accumulate.error().message();
  // And the good ones read in both forms, the brush by its name.
  const auto good =
      session_from_text(head + "{\"t\": 3000, \"cmd\": \"mode\", \"mode\": \"grab\"}\n" +
                            "{\"t\": 3001, \"cmd\": \"accumulate\", \"on\": true}\n",
                        "good.jsonl");
  ASSERT_TRUE(good.ok()) << good.error().message();
  ASSERT_EQ(good->records.size(), 4u);
  EXPECT_EQ(good->records[2].command.choice, static_cast<uint8_t>(SculptModeId::kGrab));
  EXPECT_EQ(good->records[3].command.kind, CommandKind::kAccumulate);
  EXPECT_EQ(good->records[3].command.choice, 1);
  const auto binary = parse_session_bytes(serialize_session(*good), "good.scs");
  ASSERT_TRUE(binary.ok()) << binary.error().message();
  EXPECT_EQ(*binary, *good);
}

// A custom tool's scale (issue 23): read in both forms, bit for bit; out of
// range, the binary reader stops at it with a warning and the text reader
// refuses the line.
TEST(CommandLimits, ToolScaleReadsInBothFormsAndIsRangeChecked) {
  const std::string head = session_to_text(with(command(CommandKind::kPress, 0, {})));
  const auto good = session_from_text(
      head + "{\"t\": 3000, \"cmd\": \"tool_scale\", \"value\": 1.25}\n", "good.jsonl");
  ASSERT_TRUE(good.ok()) << good.error().message();
  ASSERT_EQ(good->records.size(), 3u);
  EXPECT_EQ(good->records[2].command.kind, CommandKind::kToolScale);
  EXPECT_EQ(good->records[2].command.values[0], 1.25f);
  const auto binary = parse_session_bytes(serialize_session(*good), "good.scs");
  ASSERT_TRUE(binary.ok()) << binary.error().message();
  EXPECT_EQ(*binary, *good);
  EXPECT_EQ(session_to_text(*binary), session_to_text(*good));

  SessionReadInfo info;
  const auto r = parse_session_bytes(
      serialize_session(with(command(CommandKind::kToolScale, 0, {20.0f}))), "bad.scs", &info);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->records.size(), 1u);
  EXPECT_NE(info.warning.find("bad.scs: record 2: tool_scale command: tool scale 20 is outside"),
            std::string::npos)
      << info.warning;
  const auto bad = session_from_text(
      head + "{\"t\": 3000, \"cmd\": \"tool_scale\", \"value\": 0}\n", "bad.jsonl");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message().find("bad.jsonl:4: tool_scale: tool scale 0 is outside"),
            std::string::npos)
      << bad.error().message();
}

TEST(CommandLimits, MorphologyReadsInBothFormsByItsOperationsName) {
  const std::string head = session_to_text(with(command(CommandKind::kPress, 0, {})));
  const auto good = session_from_text(
      head + "{\"t\": 3000, \"cmd\": \"morphology\", \"op\": \"close\", \"by\": 2.5}\n" +
          "{\"t\": 3001, \"cmd\": \"morphology\", \"op\": \"offset\", \"by\": -1}\n",
      "good.jsonl");
  ASSERT_TRUE(good.ok()) << good.error().message();
  ASSERT_EQ(good->records.size(), 4u);
  EXPECT_EQ(good->records[2].command.choice, kMorphologyClose);
  EXPECT_EQ(good->records[2].command.values[0], 2.5f);
  EXPECT_EQ(good->records[3].command.choice, kMorphologyOffset);
  const auto binary = parse_session_bytes(serialize_session(*good), "good.scs");
  ASSERT_TRUE(binary.ok()) << binary.error().message();
  EXPECT_EQ(*binary, *good);
  const auto bad = session_from_text(
      head + "{\"t\": 3000, \"cmd\": \"morphology\", \"op\": \"open\", \"by\": 1}\n", "bad.jsonl");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message().find("bad.jsonl:4: op: unknown value \"open\""),
            std::string::npos)
      << bad.error().message();
}

TEST(CommandLimits, TheTextFormRefusesTheSameWithTheLine) {
  std::string text = session_to_text(with(command(CommandKind::kPress, 0, {})));
  text += "{\"t\": 3000, \"cmd\": \"tool\", \"shape\": \"sphere\", \"size\": [1e39, 2]}\n";
  const auto r = session_from_text(text, "bad.jsonl");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message().find("bad.jsonl:4: tool: value 0 is not a finite number"),
            std::string::npos)
      << r.error().message();
}

}  // namespace
}  // namespace sculpt::sim
