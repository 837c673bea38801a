// `sculpt replay` and `sculpt session` from the command line.

#include <gtest/gtest.h>

#include "scratch_dir.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "run_sculpt.h"
#include "sculpt/core/volume/material_bounds.h"
#include "sculpt/sim/synth/bundled_sessions.h"
#include "sculpt/station/project/project_file.h"

namespace sculpt::station::test {
namespace {

namespace fs = std::filesystem;

class ReplayCommandTest : public ::testing::Test {
 protected:
  sculpt::test::ScratchDir scratch_;
  const fs::path& dir_ = scratch_.path();
  std::string path(const std::string& name) const { return scratch_.file(name); }
  const std::string short_ = sculpt::sim::bundled_session_path("short");
};

TEST_F(ReplayCommandTest, ADamagedStartProjectIsOneClearError) {
  // A session's start project (session_start.h) that is not a project.
  const std::string session = path("s.scs");
  fs::copy_file(short_, session);
  {
    std::ofstream bad(session + ".start.sculpt");
    bad << "not a project";
  }
  const CommandResult r = run_sculpt("replay " + session + " --fast --stats " + path("s.json"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("s.scs.start.sculpt: not a sculpt project file"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "s.json"));
}

TEST_F(ReplayCommandTest, AProjectOpensOnItsSculptureFramed) {
  // The bust's block is 512^3: a view of a 256^3 block's centre (the
  // default) would show the sculpture's lower half from close by.
  const CommandResult r = run_sculpt("replay " + sculpt::sim::bundled_session_path("bust") +
                                     " --fast --project " + path("p.sculpt"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto project = load_project(path("p.sculpt"));
  ASSERT_TRUE(project.ok()) << project.error().message();
  const auto bounds = core::material_bounds(*project->volume);
  ASSERT_TRUE(bounds.has_value());
  OrbitCamera framed;
  framed.frame(glm::vec3(bounds->lo), glm::vec3(bounds->hi));
  const ProjectView& v = project->view;
  for (int a = 0; a < 3; ++a)
    EXPECT_FLOAT_EQ(v.camera_target[a], framed.target()[a]) << a;
  EXPECT_FLOAT_EQ(v.camera_distance, framed.distance());
  EXPECT_FLOAT_EQ(v.camera_yaw, framed.yaw());
  EXPECT_FLOAT_EQ(v.camera_pitch, framed.pitch());
}

TEST_F(ReplayCommandTest, AForceSessionWritesItsTicksRunAgainAndItsHapticFigures) {
  const std::string touch = sculpt::sim::bundled_session_path("touch");
  const CommandResult r = run_sculpt("replay " + touch + " --fast --forces " + path("f.jsonl") +
                                     " --stats " + path("s.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("6200 ticks run again, 0 forces differ from the recording"),
            std::string::npos)
      << r.out;
  const auto stats = nlohmann::json::parse(read_text(dir_ / "s.json"));
  EXPECT_EQ(stats["haptics"]["ticks"].get<int>(), 6200);
  EXPECT_EQ(stats["haptics"]["force_mismatches"].get<int>(), 0);
  std::ifstream forces(dir_ / "f.jsonl");
  int lines = 0, in_contact = 0;
  for (std::string line; std::getline(forces, line); ++lines) {
    const auto j = nlohmann::json::parse(line);
    EXPECT_FALSE(j.contains("differs_from_recording")) << line;
    if (j["contact"].get<bool>()) ++in_contact;
  }
  EXPECT_EQ(lines, 6200);
  EXPECT_GT(in_contact, 2000);  // it rested on the clay, slid and carved
}

TEST_F(ReplayCommandTest, AForceSessionWithABadLoopSetUpIsOneClearErrorAndWritesNothing) {
  // A hand-written session whose loop set-up names a setting there is not.
  const std::string session = path("bad.jsonl");
  {
    std::ofstream out(session);
    out << R"({"sculpt_session": 1, "device": {"vendor_product": "256f:c635"}})"
           "\n"
        << R"({"t": 1, "haptic": "start", "settings": "coupling.stifness_n_per_mm = 3\n"})"
           "\n";
  }
  const CommandResult r = run_sculpt("replay " + session + " --fast --forces " + path("f.jsonl") +
                                     " --stats " + path("s.json"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("bad.jsonl: haptic loop set-up: unknown setting coupling.stifness_n_per_mm"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "f.jsonl"));
  EXPECT_FALSE(fs::exists(dir_ / "s.json"));
}

TEST_F(ReplayCommandTest, WritesVolumeMeshStatsAndSamples) {
  const CommandResult r =
      run_sculpt("replay " + short_ + " --fast --volume " + path("v.nrrd") + " --mesh " +
                 path("m.ply") + " --stats " + path("s.json") + " --samples " + path("x.jsonl"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"v.nrrd", "m.ply", "s.json", "x.jsonl"})
    EXPECT_TRUE(fs::exists(dir_ / f)) << f;
  const auto stats = nlohmann::json::parse(read_text(dir_ / "s.json"));
  EXPECT_GT(stats["dabs"].get<int>(), 50);
  EXPECT_GT(stats["triangles"].get<int>(), 1000);
  EXPECT_GT(stats["dab_latency_us"]["count"].get<int>(), 50);
  EXPECT_TRUE(stats["volume_hash"].is_number_unsigned());
  // Every dab (and mirror image) places the tool once through the cache.
  EXPECT_GE(stats["rotation_cache"]["placements"].get<int>(), stats["dabs"].get<int>());
  const double hit_rate = stats["rotation_cache"]["voxel_hit_rate"].get<double>();
  EXPECT_GE(hit_rate, 0.0);
  EXPECT_LE(hit_rate, 1.0);
  // One JSON object a line, the first the device's connection.
  std::ifstream samples(dir_ / "x.jsonl");
  std::string first;
  std::getline(samples, first);
  EXPECT_TRUE(nlohmann::json::parse(first)["connected"].get<bool>());
}

TEST_F(ReplayCommandTest, TextAndBinaryConvertWithoutLossAndReplayAlike) {
  ASSERT_EQ(run_sculpt("session to-text " + short_ + " " + path("s.jsonl")).exit_code, 0);
  ASSERT_EQ(run_sculpt("session from-text " + path("s.jsonl") + " " + path("s.scs")).exit_code, 0);
  EXPECT_EQ(read_text(path("s.scs")), read_text(short_));
  const CommandResult a = run_sculpt("replay " + short_ + " --fast");
  const CommandResult b = run_sculpt("replay " + path("s.jsonl") + " --fast --threads 1");
  ASSERT_EQ(a.exit_code, 0);
  ASSERT_EQ(b.exit_code, 0);
  auto hash = [](const std::string& out) { return out.substr(out.find("volume hash")); };
  EXPECT_EQ(hash(a.out), hash(b.out));
}

TEST_F(ReplayCommandTest, ACutOffRecordingReplaysWhatItHoldsAndSaysWhatWasLost) {
  std::string bytes = read_text(short_);
  bytes.resize(bytes.size() * 2 / 3 + 5);
  std::ofstream(dir_ / "cut.scs", std::ios::binary) << bytes;
  const CommandResult r = run_sculpt("replay " + path("cut.scs") + " --fast");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("cut.scs: cut off in the middle of record"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("bytes lost"), std::string::npos);
}

TEST_F(ReplayCommandTest, BadInputIsRefusedWithOneLineAndNoOutput) {
  std::ofstream(dir_ / "junk.scs") << "\x89SCS\r\n\x1a\n\x07";
  const CommandResult junk =
      run_sculpt("replay " + path("junk.scs") + " --volume " + path("v.nrrd"));
  EXPECT_EQ(junk.exit_code, 1);
  EXPECT_EQ(line_count(junk.err), 1) << junk.err;
  EXPECT_FALSE(fs::exists(dir_ / "v.nrrd"));
  const CommandResult format = run_sculpt("replay " + short_ + " --mesh " + path("m.xyz"));
  EXPECT_EQ(format.exit_code, 1);
  EXPECT_NE(format.err.find("m.xyz"), std::string::npos) << format.err;
  EXPECT_EQ(run_sculpt("replay " + short_ + " --fast --speed 2").exit_code, 2);
  EXPECT_EQ(run_sculpt("session generate nope " + path("n.scs")).exit_code, 1);
  EXPECT_EQ(run_sculpt("session explode a b").exit_code, 2);
}

}  // namespace
}  // namespace sculpt::station::test

namespace sculpt::station::test {
namespace {

// The README's main job: no device, the demo session, results in a folder.
TEST_F(ReplayCommandTest, MainJobReplaysTheDemoAndWritesPictureMeshVolumeAndStats) {
  const CommandResult r = run_sculpt("run --headless --out " + path("out"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"sculpture.png", "sculpture.ply", "volume.nrrd", "stats.json"}) {
    EXPECT_TRUE(fs::exists(dir_ / "out" / f)) << f;
  }
  const auto stats = nlohmann::json::parse(read_text(dir_ / "out" / "stats.json"));
  EXPECT_GT(stats["dabs"].get<int>(), 200);
  EXPECT_EQ(stats["volume_dims"], nlohmann::json::array({256, 256, 256}));
  // PNG signature and the size of the picture.
  const std::string png = read_text(dir_ / "out" / "sculpture.png");
  ASSERT_GT(png.size(), 24u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_EQ(run_sculpt("run --device hidapi:/dev/hidraw9 --out " + path("o2")).exit_code, 1);
}

}  // namespace
}  // namespace sculpt::station::test

#include "sculpt/sim/session/session_file.h"

namespace sculpt::station::test {
namespace {

// Recording a session played as a live device through the reader thread's
// raw tap gives back its records exactly, up to the unplug that ends it, and
// the normaliser settings it played through (its own, not the user's
// input.conf, which here differs): the recording replays the same.
TEST_F(ReplayCommandTest, RecordCapturesTheRawReportsOfALiveDevice) {
  const auto original = sculpt::sim::read_session_file(short_);
  ASSERT_TRUE(original.ok());
  std::ofstream(dir_ / "input.conf") << "deadzone = 0.4\ncurve = cubic 0.5\n";
  ::setenv("SCULPT_INPUT_CONFIG", path("input.conf").c_str(), 1);
  const CommandResult r =
      run_sculpt("record --device sim:" + short_ + " --speed 20 -o " + path("rec.scs"));
  ::unsetenv("SCULPT_INPUT_CONFIG");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("the device was unplugged"), std::string::npos) << r.out;
  const auto recorded = sculpt::sim::read_session_file(path("rec.scs"));
  ASSERT_TRUE(recorded.ok()) << recorded.error().message();
  EXPECT_EQ(recorded->header.normalizer_config, original->header.normalizer_config);
  const auto removal =
      std::find_if(original->records.begin(), original->records.end(), [](const auto& rec) {
        return rec.kind == sculpt::sim::SessionRecord::Kind::kEvent &&
               rec.event.kind == hal::RawEventKind::kRemoved;
      });
  ASSERT_NE(removal, original->records.end());
  const std::vector<sculpt::sim::SessionRecord> expected(original->records.begin(), removal + 1);
  EXPECT_EQ(recorded->records, expected);
  EXPECT_EQ(run_sculpt("record --device 1234:5678 -o " + path("none.scs")).exit_code, 1);
  EXPECT_FALSE(fs::exists(dir_ / "none.scs"));
}

TEST_F(ReplayCommandTest, OneBadOutputLeavesNoneOfTheOthers) {
  const std::string bad = path("missing") + "/s.json";
  const CommandResult r = run_sculpt("replay " + short_ + " --fast --volume " + path("v.nrrd") +
                                     " --mesh " + path("m.ply") + " --stats " + bad);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(bad), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("v.nrrd")));
  EXPECT_FALSE(fs::exists(path("m.ply")));
  EXPECT_TRUE(fs::is_empty(dir_)) << "staged files left behind";
}

}  // namespace
}  // namespace sculpt::station::test
