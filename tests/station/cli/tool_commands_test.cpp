// `sculpt stamp`, `sculpt rotate` and `sculpt devices` from the command line.

#include <gtest/gtest.h>

#include "scratch_dir.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "run_sculpt.h"
#include "sculpt/core/io/nrrd.h"

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
  EXPECT_EQ(names, (std::vector<std::string>{"spnav", "hidapi", "evdev", "libusb"}));
  EXPECT_TRUE(j.contains("summary"));
}

}  // namespace
}  // namespace sculpt::station::test
