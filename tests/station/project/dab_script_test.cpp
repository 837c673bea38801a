// Dab scripts read field by field: every wrong type or range is one error in
// our words naming the script's line, never the JSON library's text and
// never undefined behaviour.

#include "sculpt/station/project/dab_script.h"

#include <sstream>

#include <gtest/gtest.h>

namespace sculpt::station::dab_script {
namespace {

Result<std::vector<Line>> parse_text(const std::string& text) {
  std::istringstream in(text);
  return parse(in, "s.jsonl", glm::ivec3(64));
}

TEST(DabScript, ReadsEveryOperationWithItsLine) {
  const auto script = parse_text(
      "# a comment\n"
      R"({"op":"tool","shape":"cylinder","radius":4,"height":9})"
      "\n\n"
      R"({"op":"dab","at":[10,20,30],"mode":"subtract","strength":0.5,"euler":[0,90,0]})"
      "\n"
      R"({"op":"mirror","axis":"x","centre":31.5})"
      "\n");
  ASSERT_TRUE(script.ok()) << script.error().message();
  ASSERT_EQ(script->size(), 3u);
  EXPECT_EQ((*script)[0].number, 2);
  EXPECT_EQ((*script)[1].number, 4);
  const auto& tool = std::get<ToolOp>((*script)[0].op);
  EXPECT_EQ(tool.shape, "cylinder");
  EXPECT_EQ(tool.b, 9.0);
  const auto& dab = std::get<core::Dab>((*script)[1].op);
  EXPECT_EQ(dab.mode, core::SculptMode::kSubtract);
  EXPECT_EQ(dab.position_vox, glm::vec3(10, 20, 30));
}

// Reproducers from the hardening review: a string field holding a number
// threw nlohmann's own message naming no line; a region box of 1e300 was
// converted to int (undefined); a dab at 1e30 and a radius of 500 (3.9 GB)
// were accepted.
TEST(DabScript, RefusesWrongTypesAndRangesNamingTheLine) {
  struct Case {
    const char* line;
    const char* message;
  };
  const Case cases[] = {
      {R"({"op":"sampling","value":3})", "s.jsonl:1: sampling: 'value' must be a string"},
      {R"({"op":"mirror","axis":["x"]})", "s.jsonl:1: mirror: 'axis' must be a string"},
      {R"({"op":"tool","shape":"sphere","radius":4}
{"op":"dab","at":[1,2,3],"mode":{}})",
       "s.jsonl:2: dab: 'mode' must be a string"},
      {R"({"op":"tool","shape":"region","box":[0,0,0,1e300,1,1]})",
       "s.jsonl:1: tool region: 'box' must be a non-empty box inside the volume"},
      {R"({"op":"dab","at":[1e30,2,3]})", "s.jsonl:1: dab: 'at' is more than 257 voxels outside"},
      {R"({"op":"tool","shape":"sphere","radius":500})", "'radius' must be in (0, 256]"},
      {R"({"op":"mirror","axis":"y","centre":1e20})", "mirror: 'centre' is farther than"},
      {R"({"op":"dab","at":[1,2,3],"quat":[0,0,0,0]})", "dab: 'quat' must not be zero"},
      {"{\"op\":\"dab\",\"at\":[1,2,3]", "s.jsonl:1: not valid JSON"},
  };
  for (const Case& c : cases) {
    const auto script = parse_text(c.line);
    ASSERT_FALSE(script.ok()) << c.line;
    EXPECT_NE(script.error().message().find(c.message), std::string::npos)
        << c.line << " -> " << script.error().message();
  }
}

TEST(DabScript, AMissingFileOrAFolderIsNamed) {
  const auto missing = read("/nonexistent/s.jsonl", glm::ivec3(8));
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message().find("/nonexistent/s.jsonl"), std::string::npos);
  const auto folder = read("/tmp", glm::ivec3(8));
  ASSERT_FALSE(folder.ok());
  EXPECT_NE(folder.error().message().find("/tmp: is a directory"), std::string::npos)
      << folder.error().message();
}

TEST(DabScript, ReadsAStrokeAndAToolsHardness) {
  const auto script =
      parse_text(R"({"op":"tool","shape":"sphere","radius":6,"hardness":0.25})"
                 "\n"
                 R"({"op":"stroke","path":[[1,2,3],[4,5,6]],"quats":[[1,0,0,0],[0,0,0,2]],)"
                 R"("mode":"subtract","strength":0.5,"spacing":1.5,"accumulate":true})"
                 "\n"
                 R"({"op":"stroke","path":[[7,8,9]]})"
                 "\n");
  ASSERT_TRUE(script.ok()) << script.error().message();
  ASSERT_EQ(script->size(), 3u);
  EXPECT_EQ(std::get<ToolOp>((*script)[0].op).hardness, 0.25);
  EXPECT_EQ(std::get<ToolOp>((*script)[0].op).scale, 1.0);  // by default
  const auto& s = std::get<SweepOp>((*script)[1].op);
  ASSERT_EQ(s.path.size(), 2u);
  EXPECT_EQ(s.path[1].position_vox, glm::vec3(4, 5, 6));
  EXPECT_EQ(s.path[1].orientation, glm::quat(0, 0, 0, 1));  // normalised
  EXPECT_EQ(s.options.mode, core::SculptMode::kSubtract);
  EXPECT_EQ(s.options.strength, 0.5f);
  EXPECT_TRUE(s.options.accumulate);
  EXPECT_EQ(s.spacing_vox, 1.5);
  // Defaults: add at full strength, no build-up, the points as samples.
  const auto& d = std::get<SweepOp>((*script)[2].op);
  EXPECT_EQ(d.options.mode, core::SculptMode::kAdd);
  EXPECT_EQ(d.options.strength, 1.0f);
  EXPECT_FALSE(d.options.accumulate);
  EXPECT_EQ(d.spacing_vox, 0.0);
  EXPECT_EQ(d.path[0].orientation, glm::quat(1, 0, 0, 0));
}

TEST(DabScript, RefusesBadStrokesAndHardnessNamingTheField) {
  struct Case {
    const char* line;
    const char* message;
  };
  const Case cases[] = {
      {R"({"op":"tool","shape":"cube","edge":4,"hardness":1.5})",
       "s.jsonl:1: tool cube: hardness must be a number in [0, 1], got 1.5"},
      {R"({"op":"tool","shape":"sphere","radius":4,"hardness":-0.1})",
       "tool sphere: hardness must be a number in [0, 1]"},
      {R"({"op":"tool","shape":"file","path":"t.nrrd","hardness":"soft"})",
       "tool file: 'hardness' must be a finite number"},
      {R"({"op":"tool","shape":"file","path":"t.nrrd","scale":9})",
       "s.jsonl:1: tool file: 'scale' must be in [0.125, 8]"},
      {R"({"op":"tool","shape":"sphere","radius":4,"scale":0.1})",
       "tool sphere: 'scale' must be in [0.125, 8]"},
      {R"({"op":"tool","shape":"region","box":[0,0,0,4,4,4],"scale":"big"})",
       "tool region: 'scale' must be a finite number"},
      {R"({"op":"stroke"})", "s.jsonl:1: stroke: 'path' must be a non-empty array"},
      {R"({"op":"stroke","path":[]})", "stroke: 'path' must be a non-empty array"},
      {R"({"op":"stroke","path":[[1,2,3],[1,2]]})", "stroke: 'path' must be a non-empty array"},
      {R"({"op":"stroke","path":[[1,2,3],[1,"2",3]]})", "stroke: 'path' point 1 must be 3 finite"},
      {R"({"op":"stroke","path":[[1,2,3],[1e30,2,3]]})",
       "stroke: 'path' point 1 is more than 257 voxels outside the volume"},
      {R"({"op":"stroke","path":[[1,2,3]],"quats":[]})", "stroke: 'quats' must hold one"},
      {R"({"op":"stroke","path":[[1,2,3]],"quats":[[0,0,0,0]]})",
       "stroke: 'quats' entry 0 must not be zero"},
      {R"({"op":"stroke","path":[[1,2,3]],"quats":[[1,0,0]]})",
       "stroke: 'quats' entry 0 must be 4 finite numbers"},
      {R"({"op":"stroke","path":[[1,2,3]],"mode":"smooth"})", "stroke: unknown mode 'smooth'"},
      {R"({"op":"stroke","path":[[1,2,3]],"mode":7})", "stroke: 'mode' must be a string"},
      {R"({"op":"stroke","path":[[1,2,3]],"strength":1.5})",
       "stroke: 'strength' must be a number in [0, 1]"},
      {R"({"op":"stroke","path":[[1,2,3]],"spacing":0})",
       "stroke: 'spacing' must be a number above 0"},
      {R"({"op":"stroke","path":[[0,0,0],[60,60,60]],"spacing":1e-6})",
       "stroke: 'spacing' places more than 1000000 samples"},
      {R"({"op":"stroke","path":[[1,2,3]],"accumulate":"yes"})",
       "stroke: 'accumulate' must be true or false"},
  };
  for (const Case& c : cases) {
    const auto script = parse_text(c.line);
    ASSERT_FALSE(script.ok()) << c.line;
    EXPECT_NE(script.error().message().find(c.message), std::string::npos)
        << c.line << " -> " << script.error().message();
  }
}

}  // namespace
}  // namespace sculpt::station::dab_script
