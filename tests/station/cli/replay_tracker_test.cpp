// `sculpt replay` of a tracker's session: the recorded OpenTrack datagrams
// are decoded again into absolute poses, a lost tracker ends the stroke, and
// a malformed recorded datagram is counted and dropped.

#include <gtest/gtest.h>

#include "scratch_dir.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "run_sculpt.h"
#include "sculpt/hal/parsers/opentrack_datagram.h"

namespace sculpt::station::test {
namespace {

std::string hex(std::span<const uint8_t> bytes) {
  std::string s;
  char b[4];
  for (uint8_t v : bytes) {
    std::snprintf(b, sizeof b, "%02x", v);
    s += b;
  }
  return s;
}

std::string datagram_line(int64_t t_ns, double x_cm, double y_cm, double z_cm, double yaw_deg) {
  const auto bytes = hal::encode_opentrack_datagram(x_cm, y_cm, z_cm, yaw_deg, 0, 0);
  return R"({"t": )" + std::to_string(t_ns) + R"(, "report": ")" + hex(bytes) + "\"}\n";
}

TEST(ReplayTracker, SamplesHoldTheRecordedPosesAndTrackingLost) {
  sculpt::test::ScratchDir scratch;
  const std::string session = scratch.file("opentrack.jsonl");
  {
    std::ofstream out(session);
    out << R"({"sculpt_session": 1, "device": {"backend": "opentrack", "path": "127.0.0.1:4242", )"
           R"("vendor_product": "0000:0000", "name": "OpenTrack"}})"
        << "\n"
        << datagram_line(1'000'000, 1.0, 2.0, 3.0, 0) << R"({"t": 2000000, "cmd": "press"})"
        << "\n"
        << datagram_line(3'000'000, 1.5, 2.0, 3.0, 90) << R"({"t": 4000000, "report": "00 01 02"})"
        << "\n"  // short: counted, dropped
        << R"({"t": 5000000, "report": ""})"
        << "\n"  // tracking lost
        << datagram_line(6'000'000, 40.0, 2.0, 3.0, 0);
  }
  const CommandResult r =
      run_sculpt("replay " + session + " --fast --samples " + scratch.file("s.jsonl") +
                 " --stats " + scratch.file("stats.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<nlohmann::json> samples;
  std::ifstream in(scratch.file("s.jsonl"));
  for (std::string line; std::getline(in, line);)
    samples.push_back(nlohmann::json::parse(line));
  std::vector<nlohmann::json> poses;
  int lost = 0;
  for (const auto& j : samples) {
    if (j.contains("pose")) poses.push_back(j);
    if (j.contains("tracking_lost")) ++lost;
    EXPECT_FALSE(j.contains("motion")) << j.dump();
  }
  ASSERT_EQ(poses.size(), 3u);
  EXPECT_EQ(lost, 1);
  EXPECT_EQ(poses[0]["device"], 0);
  EXPECT_EQ(poses[0]["t"], 1'000'000);
  EXPECT_EQ(poses[0]["pose"]["position_mm"], nlohmann::json({10.0, 20.0, 30.0}));
  EXPECT_EQ(poses[0]["pose"]["quat"], nlohmann::json({1.0, 0.0, 0.0, 0.0}));
  EXPECT_EQ(poses[1]["pose"]["position_mm"][0].get<double>(), 15.0);
  // Yaw 90 degrees about +Y.
  EXPECT_NEAR(poses[1]["pose"]["quat"][0].get<double>(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(poses[1]["pose"]["quat"][2].get<double>(), std::sqrt(0.5), 1e-12);
  EXPECT_EQ(poses[2]["pose"]["position_mm"][0].get<double>(), 400.0);

  const auto stats = nlohmann::json::parse(read_text(scratch.file("stats.json")));
  EXPECT_EQ(stats["short_reports"].get<int>(), 1);
  EXPECT_EQ(stats["tracking_losses"].get<int>(), 1);
  EXPECT_EQ(stats["strokes"].get<int>(), 1);
}

TEST(ReplayTracker, ATrackerSessionReplaysToTheSameSculptureEveryTime) {
  sculpt::test::ScratchDir scratch;
  const std::string session = scratch.file("t.jsonl");
  {
    std::ofstream out(session);
    out << R"({"sculpt_session": 1, "device": {"backend": "opentrack", "path": "127.0.0.1:4242", )"
           R"("vendor_product": "0000:0000"}})"
        << "\n"
        << R"({"t": 1, "cmd": "volume", "size": [64, 64, 64], "clay_margin": 8})"
        << "\n"
        << datagram_line(1'000'000, 0, 0, 0, 0) << R"({"t": 1500000, "cmd": "press"})"
        << "\n";
    for (int i = 1; i <= 20; ++i)
      out << datagram_line(1'000'000 + i * 1'000'000, 0.1 * i, 0, 0, 0);
  }
  const CommandResult a = run_sculpt("replay " + session + " --fast --stats " + scratch.file("a"));
  const CommandResult b = run_sculpt("replay " + session + " --fast --stats " + scratch.file("b"));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const auto sa = nlohmann::json::parse(read_text(scratch.file("a")));
  const auto sb = nlohmann::json::parse(read_text(scratch.file("b")));
  EXPECT_GT(sa["dabs"].get<int>(), 1) << "the tracker's 20 mm stroke sculpted";
  EXPECT_EQ(sa["volume_hash"], sb["volume_hash"]);
}

}  // namespace
}  // namespace sculpt::station::test
