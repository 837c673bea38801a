// `sculpt stamp`, `sculpt rotate` and `sculpt devices` from the command line.

#include <gtest/gtest.h>

#include "scratch_dir.h"

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <span>

#include "run_sculpt.h"
#include "sculpt/core/io/nrrd.h"
#include "sculpt/core/sculpt/clay_brush.h"
#include "sculpt/core/sculpt/flatten_brush.h"
#include "sculpt/core/sculpt/grab_brush.h"
#include "sculpt/core/sculpt/inflate_brush.h"
#include "sculpt/core/sculpt/pinch_brush.h"
#include "sculpt/core/sculpt/smooth_brush.h"
#include "sculpt/core/sculpt/stroke.h"

namespace sculpt::station::test {
namespace {

namespace fs = std::filesystem;

class ToolCommandsTest : public ::testing::Test {
 protected:
  sculpt::test::ScratchDir scratch_;
  const fs::path& dir_ = scratch_.path();
  std::string path(const std::string& name) const { return scratch_.file(name); }
};

int64_t mass(const sculpt::core::DenseGrid<uint8_t>& g) {
  int64_t m = 0;
  for (uint8_t v : g.values())
    m += v;
  return m;
}

TEST_F(ToolCommandsTest, StampThenRotateAQuarterTurnKeepsTheMaterial) {
  const std::string script = std::string(SCULPT_TEST_DATA_DIR) + "/tool/example_dabs.jsonl";
  const CommandResult stamp =
      run_sculpt("stamp --new 96,96,96 --dabs " + script + " -o " + path("s.nrrd"));
  ASSERT_EQ(stamp.exit_code, 0) << stamp.err;
  const auto sculpted = sculpt::core::read_nrrd_u8(path("s.nrrd"));
  ASSERT_TRUE(sculpted.ok());
  EXPECT_GT(mass(*sculpted), 0);
  const CommandResult rotate =
      run_sculpt("rotate " + path("s.nrrd") + " --euler 0,0,90 -o " + path("r.nrrd"));
  ASSERT_EQ(rotate.exit_code, 0) << rotate.err;
  const auto rotated = sculpt::core::read_nrrd_u8(path("r.nrrd"));
  ASSERT_TRUE(rotated.ok());
  EXPECT_EQ(mass(*rotated), mass(*sculpted));  // a quarter turn is exact
}

TEST_F(ToolCommandsTest, AToolSavedBeforeAFailingLineIsNotWritten) {
  // The script runs as far as line 3, which fails when it runs (the tool
  // file is missing): the tool line 2 saved must not appear either.
  std::ofstream(dir_ / "late.jsonl") << R"({"op":"tool","shape":"sphere","radius":4})"
                                        "\n"
                                     << R"({"op":"save_tool","path":"saved.nrrd"})"
                                        "\n"
                                     << R"({"op":"tool","shape":"file","path":"missing.nrrd"})"
                                        "\n";
  const CommandResult r =
      run_sculpt("stamp --new 32,32,32 --dabs " + path("late.jsonl") + " -o " + path("o.nrrd"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("late.jsonl:3"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "saved.nrrd"));
  EXPECT_FALSE(fs::exists(dir_ / "o.nrrd"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1)
      << "staged files left behind";
}

TEST_F(ToolCommandsTest, ARegionToolScaledTwiceIsTwiceAsLargeWithEightTimesTheVolume) {
  // A ball sculpted, its region taken as the tool at its size and at twice
  // it, both saved: the second is twice as wide and holds 8x the material.
  std::ofstream(dir_ / "scale.jsonl") << R"({"op":"tool","shape":"sphere","radius":6})"
                                         "\n"
                                      << R"({"op":"dab","at":[16,16,16],"mode":"add"})"
                                         "\n"
                                      << R"({"op":"tool","shape":"region","box":[6,6,6,26,26,26]})"
                                         "\n"
                                      << R"({"op":"save_tool","path":"one.nrrd"})"
                                         "\n"
                                      << R"({"op":"tool","shape":"region","box":[6,6,6,26,26,26],)"
                                         R"("scale":2})"
                                         "\n"
                                      << R"({"op":"save_tool","path":"two.nrrd"})"
                                         "\n";
  const CommandResult r =
      run_sculpt("stamp --new 32,32,32 --dabs " + path("scale.jsonl") + " -o " + path("o.nrrd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto one = sculpt::core::read_nrrd_u8(path("one.nrrd"));
  const auto two = sculpt::core::read_nrrd_u8(path("two.nrrd"));
  ASSERT_TRUE(one.ok() && two.ok());
  EXPECT_EQ(one->dims(), glm::ivec3(20));
  EXPECT_EQ(two->dims(), glm::ivec3(40));
  EXPECT_GT(mass(*one), 0);
  EXPECT_NEAR(static_cast<double>(mass(*two)), 8.0 * static_cast<double>(mass(*one)),
              0.01 * 8.0 * static_cast<double>(mass(*one)));
}

TEST_F(ToolCommandsTest, AToolScaledPastTheSizeLimitIsRefusedBeforeItIsMade) {
  // 200^3 x 8 would be 1600 voxels on an edge (4 GiB): one line, nothing written.
  std::ofstream(dir_ / "big.jsonl") << R"({"op":"tool","shape":"region","box":[0,0,0,200,200,200],)"
                                       R"("scale":8})"
                                       "\n";
  const CommandResult r =
      run_sculpt("stamp --new 200,200,200 --dabs " + path("big.jsonl") + " -o " + path("o.nrrd"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("big.jsonl:1: the scaled tool would be larger than 1024"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "o.nrrd"));
}

TEST_F(ToolCommandsTest, ANewVolumeBeyondTwoToThe32VoxelsIsRefused) {
  std::ofstream(dir_ / "one.jsonl") << R"({"op":"tool","shape":"sphere","radius":4})"
                                       "\n";
  const CommandResult r = run_sculpt("stamp --new 65536,65536,256 --dabs " + path("one.jsonl") +
                                     " -o " + path("o.nrrd"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("--new"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "o.nrrd"));
}

TEST_F(ToolCommandsTest, BadScriptLineIsNamedAndNothingIsWritten) {
  std::ofstream(dir_ / "bad.jsonl") << R"({"op":"tool","shape":"sphere","radius":4})"
                                       "\n"
                                    << R"({"op":"dab","at":[1,2]})"
                                       "\n";
  const CommandResult r =
      run_sculpt("stamp --new 32,32,32 --dabs " + path("bad.jsonl") + " -o " + path("o.nrrd"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("bad.jsonl:2"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "o.nrrd"));
  EXPECT_EQ(run_sculpt("rotate " + path("missing.nrrd") + " --euler 1,2,3 -o " + path("x.nrrd"))
                .exit_code,
            1);
  // Two angles where three are needed: the option's value is bad input.
  const CommandResult two =
      run_sculpt("rotate " + path("missing.nrrd") + " --euler 1,2 -o " + path("x.nrrd"));
  EXPECT_EQ(two.exit_code, 1);
  EXPECT_EQ(line_count(two.err), 1) << two.err;
}

TEST_F(ToolCommandsTest, DevicesListsEveryBackendAsJson) {
  const CommandResult r = run_sculpt("devices --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;  // enumeration works here even with nothing attached
  const auto j = nlohmann::json::parse(r.out);
  std::vector<std::string> names;
  for (const auto& b : j["backends"])
    names.push_back(b["name"]);
  EXPECT_EQ(names, (std::vector<std::string>{"spnav", "hidapi", "evdev", "libusb", "openxr"}));
  EXPECT_TRUE(j.contains("summary"));
}

// The stroke op runs the core's sweep: the volume is the one sweep_stroke()
// makes through the same points with the same (softened) tool; with a
// "spacing" the station's sampler re-places the samples, and a straight
// stroke's result does not depend on where.
TEST_F(ToolCommandsTest, StampStrokeIsTheCoreSweep) {
  std::ofstream(dir_ / "stroke.jsonl")
      << R"({"op":"tool","shape":"sphere","radius":6,"hardness":0.5})"
         "\n"
      << R"({"op":"stroke","path":[[10,30.5,32],[30,33,34],[54,33,30]],"mode":"add","strength":0.7})"
         "\n";
  const CommandResult r = run_sculpt("stamp --new 64,64,64 --dabs " + path("stroke.jsonl") +
                                     " -o " + path("stroke.nrrd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("1 swept strokes through 3 samples"), std::string::npos) << r.out;
  const auto stamped = sculpt::core::read_nrrd_u8(path("stroke.nrrd"));
  ASSERT_TRUE(stamped.ok());
  sculpt::core::Volume v(glm::ivec3(64), uint8_t{0});
  sculpt::core::Sculptor sculptor(v);
  sculptor.set_tool(sculpt::core::make_sphere_tool(6.0f, 0.5f));
  const std::vector<sculpt::core::StrokeSample> samples = {
      {{10.0f, 30.5f, 32.0f}, {}}, {{30.0f, 33.0f, 34.0f}, {}}, {{54.0f, 33.0f, 30.0f}, {}}};
  (void)sculpt::core::sweep_stroke(sculptor, samples,
                                   {sculpt::core::SculptMode::kAdd, 0.7f, false});
  EXPECT_EQ(stamped->values(), v.to_dense().values());

  std::ofstream(dir_ / "spaced.jsonl")
      << R"({"op":"tool","shape":"sphere","radius":6})"
         "\n"
      << R"({"op":"stroke","path":[[10,32,32],[54,32,32]],"spacing":4})"
         "\n"
      << R"({"op":"stroke","path":[[10,32,12],[54,32,12]]})"
         "\n";
  const CommandResult spaced = run_sculpt("stamp --new 64,64,64 --dabs " + path("spaced.jsonl") +
                                          " -o " + path("spaced.nrrd"));
  ASSERT_EQ(spaced.exit_code, 0) << spaced.err;
  EXPECT_NE(spaced.out.find("2 swept strokes through 14 samples"), std::string::npos) << spaced.out;
  const auto g = sculpt::core::read_nrrd_u8(path("spaced.nrrd"));
  ASSERT_TRUE(g.ok());
  int worst = 0;
  for (int z = 0; z < 20; ++z)
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x)
        worst = std::max(worst, std::abs(int(g->at(x, y, z + 20)) - int(g->at(x, y, z))));
  EXPECT_LE(worst, 1);
}

TEST_F(ToolCommandsTest, BadStrokeOrHardnessIsNamedAndNothingIsWritten) {
  for (const char* bad : {R"({"op":"stroke","path":[[1,2,3]],"quats":[[1,0,0,0],[1,0,0,0]]})",
                          R"({"op":"stroke","path":[[1,2,3]],"strength":-1})",
                          R"({"op":"tool","shape":"sphere","radius":4,"hardness":2})"}) {
    std::ofstream(dir_ / "bad.jsonl") << R"({"op":"tool","shape":"sphere","radius":4})"
                                         "\n"
                                      << R"({"op":"stroke","path":[[1,2,3],[9,9,9]]})"
                                         "\n"
                                      << bad << "\n";
    const CommandResult r =
        run_sculpt("stamp --new 32,32,32 --dabs " + path("bad.jsonl") + " -o " + path("o.nrrd"));
    EXPECT_EQ(r.exit_code, 1) << bad;
    EXPECT_EQ(line_count(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("bad.jsonl:3: "), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "o.nrrd"));
  }
}

// Each ball brush op runs the core's brush: the volume is the one the
// brush function makes from the same ball with the same options.
TEST_F(ToolCommandsTest, StampBrushOpsAreTheCoreBrushes) {
  using namespace sculpt::core;  // NOLINT(google-build-using-namespace)
  using Apply = std::function<int64_t(Volume&, Sculptor&, std::span<const StrokeSample>)>;
  SmoothBrushOptions smooth;
  smooth.radius_vox = 6.0f;
  smooth.passes = 3;
  ClayBrushOptions clay;
  clay.layer = 0.3f;
  InflateBrushOptions inflate;
  inflate.radius_vox = 10.0f;
  inflate.distance_vox = 1.5f;
  PinchBrushOptions pinch;
  pinch.strength = 0.7f;
  GrabBrushOptions grab;
  grab.radius_vox = 10.0f;
  const std::vector<std::pair<std::string, Apply>> ops = {
      {R"({"op":"smooth","path":[[32,32,44],[40,32,42]],"radius":6,"passes":3})",
       [&](Volume& v, Sculptor& s, auto p) { return smooth_stroke(v, s, p, smooth); }},
      {R"({"op":"clay","path":[[32,32,44],[40,32,42]],"layer":0.3})",
       [&](Volume& v, Sculptor& s, auto p) { return clay_stroke(v, s, p, clay); }},
      {R"({"op":"flatten","path":[[32,32,44],[40,32,42]]})",
       [&](Volume& v, Sculptor& s, auto p) { return flatten_stroke(v, s, p, {}); }},
      {R"({"op":"inflate","path":[[32,32,44],[40,32,42]],"radius":10,"distance":1.5})",
       [&](Volume& v, Sculptor& s, auto p) { return inflate_stroke(v, s, p, inflate); }},
      {R"({"op":"pinch","path":[[32,32,44],[40,32,42]],"strength":0.7})",
       [&](Volume& v, Sculptor& s, auto p) { return pinch_stroke(v, s, p, pinch); }},
      {R"({"op":"grab","path":[[32,32,44],[40,32,42]],"radius":10})",
       [&](Volume& v, Sculptor& s, auto p) { return grab_stroke(v, s, p, grab); }},
  };
  const std::vector<StrokeSample> samples = {{{32.0f, 32.0f, 44.0f}, {}},
                                             {{40.0f, 32.0f, 42.0f}, {}}};
  for (const auto& [line, apply] : ops) {
    std::ofstream(dir_ / "brush.jsonl") << R"({"op":"tool","shape":"sphere","radius":12})"
                                           "\n"
                                        << R"({"op":"dab","at":[32,32,32]})"
                                           "\n"
                                        << line << "\n";
    const CommandResult r = run_sculpt("stamp --new 64,64,64 --dabs " + path("brush.jsonl") +
                                       " -o " + path("brush.nrrd"));
    ASSERT_EQ(r.exit_code, 0) << line << r.err;
    EXPECT_NE(r.out.find("1 brush strokes: "), std::string::npos) << r.out;
    const auto stamped = read_nrrd_u8(path("brush.nrrd"));
    ASSERT_TRUE(stamped.ok());
    Volume v(glm::ivec3(64), uint8_t{0});
    Sculptor sculptor(v);
    sculptor.set_tool(make_sphere_tool(12.0f));
    (void)sculptor.dab({{32.0f, 32.0f, 32.0f}, {}, SculptMode::kAdd, 1.0f});
    const uint64_t before = v.content_hash();
    EXPECT_GT(apply(v, sculptor, samples), 0) << line;
    EXPECT_NE(v.content_hash(), before) << line;
    EXPECT_EQ(stamped->values(), v.to_dense().values()) << line;
  }
}

TEST_F(ToolCommandsTest, BadBrushKeyOrValueIsNamedAndNothingIsWritten) {
  const std::pair<const char*, const char*> bad[] = {
      {R"({"op":"smooth","path":[[1,2,3]],"passes":0})", "smooth: 'passes'"},
      {R"({"op":"clay","path":[[1,2,3]],"strenght":1})", "clay: unknown key 'strenght'"},
      {R"({"op":"flatten","path":[[1,2,3]],"hardness":7})", "flatten: 'hardness'"},
      {R"({"op":"inflate","path":[[1,2,3]],"distance":0})", "inflate: 'distance'"},
      {R"({"op":"pinch","path":[[1,2,3]],"radius":"big"})", "pinch: 'radius'"},
      {R"({"op":"grab","path":[]})", "grab: 'path'"},
  };
  for (const auto& [line, message] : bad) {
    std::ofstream(dir_ / "bad.jsonl") << R"({"op":"tool","shape":"sphere","radius":4})"
                                         "\n"
                                      << line << "\n";
    const CommandResult r =
        run_sculpt("stamp --new 32,32,32 --dabs " + path("bad.jsonl") + " -o " + path("o.nrrd"));
    EXPECT_EQ(r.exit_code, 1) << line;
    EXPECT_EQ(line_count(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(std::string("bad.jsonl:2: ") + message), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "o.nrrd"));
  }
}

}  // namespace
}  // namespace sculpt::station::test
