// A tool given whole in a session (kToolVoxels): its voxels split over tool
// records in the binary file, one line in the text form; damaged, cut or
// out-of-range ones stop the reader with one warning naming the record.

#include <gtest/gtest.h>

#include "sculpt/sim/session/command_limits.h"
#include "sculpt/sim/session/session_file.h"
#include "sculpt/sim/session/session_text.h"

namespace sculpt::sim {
namespace {

// 50 x 40 x 40 voxels: 80000 bytes, two records.
std::shared_ptr<ToolVoxels> tool(uint16_t x = 50, uint16_t y = 40, uint16_t z = 40) {
  auto t = std::make_shared<ToolVoxels>();
  t->dims[0] = x;
  t->dims[1] = y;
  t->dims[2] = z;
  t->pivot[0] = 24.5f;
  t->pivot[1] = 19.5f;
  t->pivot[2] = 0.1f;
  t->hardness = 0.75f;
  t->density.resize(size_t{x} * y * z);
  for (size_t i = 0; i < t->density.size(); ++i)
    t->density[i] = static_cast<uint8_t>(i * 7 % 251);
  return t;
}

Session with_tool(std::shared_ptr<const ToolVoxels> voxels) {
  Session s;
  s.header.device.backend = "sim";
  s.records.push_back(SessionRecord::of(1000, Command{CommandKind::kPress}));
  Command c{CommandKind::kToolVoxels};
  c.voxels = std::move(voxels);
  s.records.push_back(SessionRecord::of(2000, c));
  s.records.push_back(SessionRecord::of(3000, Command{CommandKind::kRelease}));
  return s;
}

TEST(SessionToolVoxels, ReadBackBitForBitInBothForms) {
  const Session s = with_tool(tool());
  SessionReadInfo info;
  const auto binary = parse_session_bytes(serialize_session(s), "t.scs", &info);
  ASSERT_TRUE(binary.ok()) << binary.error().message();
  EXPECT_TRUE(info.warning.empty()) << info.warning;
  EXPECT_EQ(*binary, s);
  ASSERT_EQ(binary->records.size(), 3u);
  ASSERT_NE(binary->records[1].command.voxels, nullptr);
  EXPECT_EQ(binary->records[1].command.voxels->density, tool()->density);
  const auto text = session_from_text(session_to_text(s), "t.jsonl");
  ASSERT_TRUE(text.ok()) << text.error().message();
  EXPECT_EQ(*text, s);
  // Another tool is another command.
  EXPECT_FALSE(with_tool(tool(50, 40, 39)) == s);
}

TEST(SessionToolVoxels, ACutOrDamagedToolStopsTheReaderBeforeIt) {
  const std::vector<uint8_t> good = serialize_session(with_tool(tool()));
  const std::vector<uint8_t> press_only = [] {
    Session s = with_tool(tool());
    s.records.resize(1);
    return serialize_session(s);
  }();
  // Cut in the second record of the tool: the press is kept.
  SessionReadInfo cut;
  const auto r = parse_session_bytes({good.data(), press_only.size() + 70000}, "cut.scs", &cut);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->records.size(), 1u);
  EXPECT_NE(cut.warning.find("cut.scs: cut off in the middle of record 2"), std::string::npos)
      << cut.warning;
  EXPECT_EQ(cut.bytes_lost, 70000);
  // The first tool record alone, then the release: cut short by another record.
  std::vector<uint8_t> spliced(good.begin(), good.begin() + press_only.size() + 12 + 60000 + 4);
  const std::vector<uint8_t> tail(good.end() - (12 + 2 + 4), good.end());  // the release
  spliced.insert(spliced.end(), tail.begin(), tail.end());
  SessionReadInfo info;
  const auto s = parse_session_bytes(spliced, "s.scs", &info);
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->records.size(), 1u);
  EXPECT_NE(info.warning.find("s.scs: record 2: a tool record is cut short by another record"),
            std::string::npos)
      << info.warning;
  // A flipped byte: the record's checksum.
  std::vector<uint8_t> flipped = good;
  flipped[press_only.size() + 12 + 30] ^= 0x40;
  SessionReadInfo bad;
  ASSERT_TRUE(parse_session_bytes(flipped, "f.scs", &bad).ok());
  EXPECT_NE(bad.warning.find("f.scs: checksum mismatch in record 2"), std::string::npos)
      << bad.warning;
  // The file ending after the tool's first record.
  SessionReadInfo end;
  const auto e =
      parse_session_bytes({good.data(), press_only.size() + 12 + 60000 + 4}, "e.scs", &end);
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->records.size(), 1u);
  EXPECT_NE(end.warning.find("e.scs: cut off in the middle of the tool of record 2"),
            std::string::npos)
      << end.warning;
}

TEST(SessionToolVoxels, OutOfRangeToolsAreRefusedByBothReadersAndTheWriter) {
  auto big = tool(1, 1, 1);
  big->pivot[0] = 50.0f;  // 50 voxels outside a 1-voxel grid
  const auto why = tool_voxels_problem(*big);
  ASSERT_TRUE(why.has_value());
  EXPECT_NE(why->find("tool pivot 50 is more than the grid's size outside it"), std::string::npos);
  auto short_density = tool(4, 4, 4);
  short_density->density.resize(10);
  short_density->pivot[0] = short_density->pivot[1] = short_density->pivot[2] = 1.5f;
  EXPECT_NE(tool_voxels_problem(*short_density)->find("tool of 10 voxels where its sides make 64"),
            std::string::npos);

  SessionReadInfo info;
  const auto r = parse_session_bytes(serialize_session(with_tool(big)), "b.scs", &info);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->records.size(), 1u);
  EXPECT_NE(info.warning.find("b.scs: record 2: tool_voxels command: tool pivot 50"),
            std::string::npos)
      << info.warning;
  const auto text = session_from_text(session_to_text(with_tool(big)), "b.jsonl");
  ASSERT_FALSE(text.ok());
  EXPECT_NE(text.error().message().find("b.jsonl:3: tool_voxels: tool pivot 50"), std::string::npos)
      << text.error().message();
  // A tool_voxels command record without its voxels.
  Session bare;
  bare.records.push_back(SessionRecord::of(1, Command{CommandKind::kToolVoxels}));
  SessionReadInfo none;
  ASSERT_TRUE(parse_session_bytes(serialize_session(bare), "n.scs", &none).ok());
  EXPECT_NE(none.warning.find("n.scs: record 1: tool_voxels command: no voxels"), std::string::npos)
      << none.warning;
  EXPECT_FALSE(check_writable(SessionRecord::of(1, Command{CommandKind::kToolVoxels}), "w.scs", 0));
}

}  // namespace
}  // namespace sculpt::sim
