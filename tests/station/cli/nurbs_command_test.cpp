// The `sculpt nurbs` command-line contract (DESIGN.md §7): deform, tessellate,
// invert, example; good input does what it says, bad input is one line on
// stderr naming the input, exit 1 (2 for usage), and no output file.

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "run_sculpt.h"
#include "scratch_dir.h"
#include "sculpt/core/nurbs/nurbs_json.h"

namespace sculpt::station::test {
namespace {

namespace fs = std::filesystem;
namespace nurbs = core::nurbs;

const std::string kData = std::string(SCULPT_TEST_DATA_DIR) + "/nurbs/";

class NurbsCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const CommandResult r = run_sculpt("nurbs example -o " + path("sheet.json") + " --curve " +
                                       path("arch.json") + " --zone " + path("zone.json"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  std::string path(const std::string& name) const { return scratch_.file(name); }
  // Runs a command that must fail with exit `code`, one stderr line holding
  // `needle`, and no file at `output`.
  void expect_refused(const std::string& args, int code, const std::string& needle,
                      const std::string& output) {
    const CommandResult r = run_sculpt(args);
    EXPECT_EQ(r.exit_code, code) << args << "\n" << r.out << r.err;
    if (code == 1) {
      EXPECT_EQ(line_count(r.err), 1) << r.err;
    }
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(output)) << output;
  }
  sculpt::test::ScratchDir scratch_;
};

TEST_F(NurbsCommandTest, LinearConstraintReachesTheTargetWithEachInfluence) {
  for (const std::string& influence :
       std::vector<std::string>{"natural", "gaussian:3", "zone:" + path("zone.json")}) {
    const CommandResult r = run_sculpt("nurbs deform " + path("sheet.json") +
                                       " --uv 0.4,0.6 --to 50,60,30 --influence " + influence +
                                       " -o " + path("out.json") + " --mesh " + path("out.ply"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    Result<nurbs::NurbsSurface> s = nurbs::read_surface_json(path("out.json"));
    ASSERT_TRUE(s.ok()) << s.error().message();
    EXPECT_LT(glm::length(nurbs::evaluate(*s, 0.4, 0.6) - glm::dvec3(50, 60, 30)), 1e-9);
    EXPECT_EQ(read_text(path("out.ply")).rfind("ply\n", 0), 0u);
  }
}

TEST_F(NurbsCommandTest, PathWithRefinedZoneEndsExactlyAtTheCurvesEnd) {
  const CommandResult r = run_sculpt(
      "nurbs deform " + path("sheet.json") + " --uv 0.5,0.5 --influence zone:" + path("zone.json") +
      " --refine 100 --path " + path("arch.json") + " --steps 80 -o " + path("out.json") +
      " --mesh " + path("out.obj"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("refined to"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("80 steps"), std::string::npos) << r.out;
  Result<nurbs::NurbsSurface> s = nurbs::read_surface_json(path("out.json"));
  Result<nurbs::NurbsCurve> c = nurbs::read_curve_json(path("arch.json"));
  ASSERT_TRUE(s.ok() && c.ok());
  EXPECT_GT(s->point_count(), 150);
  EXPECT_LT(glm::length(nurbs::evaluate(*s, 0.5, 0.5) - nurbs::evaluate(*c, 1.0)), 1e-9);
  EXPECT_NE(read_text(path("out.obj")).find("\nvn "), std::string::npos);
}

TEST_F(NurbsCommandTest, PickTessellateAndInvert) {
  Result<nurbs::NurbsSurface> sheet = nurbs::read_surface_json(path("sheet.json"));
  ASSERT_TRUE(sheet.ok());
  const glm::dvec3 p = nurbs::evaluate(*sheet, 0.3, 0.7);
  char at[128], to[128];
  std::snprintf(at, sizeof at, "%.17g,%.17g,%.17g", p.x, p.y, p.z);
  std::snprintf(to, sizeof to, "%.17g,%.17g,%.17g", p.x, p.y, p.z + 5.0);
  const CommandResult pick = run_sculpt("nurbs deform " + path("sheet.json") + " --pick " + at +
                                        " --to " + to + " -o " + path("picked.json"));
  ASSERT_EQ(pick.exit_code, 0) << pick.err;
  EXPECT_NE(pick.out.find("picked      (u, v) = (0.3, 0.7)"), std::string::npos) << pick.out;
  const CommandResult inv = run_sculpt("nurbs invert " + path("picked.json") + " --point " + to);
  ASSERT_EQ(inv.exit_code, 0) << inv.err;
  // The moved point is on the deformed sheet at the same parameters.
  auto value = [&](const std::string& key) {
    const size_t at_key = inv.out.find("\n" + key + " ");
    return at_key == std::string::npos
               ? -1.0
               : std::strtod(inv.out.c_str() + at_key + key.size() + 2, nullptr);
  };
  EXPECT_NEAR(std::strtod(inv.out.c_str() + 2, nullptr), 0.3, 1e-9) << inv.out;
  EXPECT_NEAR(value("v"), 0.7, 1e-9) << inv.out;
  EXPECT_NEAR(value("distance"), 0.0, 1e-9) << inv.out;
  for (const char* out : {"t.obj", "t.ply", "t.stl"}) {
    const CommandResult t =
        run_sculpt("nurbs tessellate " + path("sheet.json") + " --per-span 2 -o " + path(out));
    ASSERT_EQ(t.exit_code, 0) << t.err;
    // 12 x 7 spans, 2 cells each, 2 triangles per cell.
    EXPECT_NE(t.out.find("(672 triangles"), std::string::npos) << t.out;
  }
  const CommandResult ff =
      run_sculpt("nurbs tessellate " + path("sheet.json") + " --freeform -o " + path("ff.obj"));
  ASSERT_EQ(ff.exit_code, 0) << ff.err;
  EXPECT_NE(read_text(path("ff.obj")).find("cstype bspline\ndeg 3 3\nsurf 0 1 0 1 1 2"),
            std::string::npos);
}

TEST_F(NurbsCommandTest, BadInputIsOneLineNamingItAndNoOutput) {
  const std::string sheet = path("sheet.json");
  const std::string out = path("out.json");
  expect_refused("nurbs deform " + path("none.json") + " --uv 0.5,0.5 --to 1,2,3 -o " + out, 1,
                 "none.json: cannot open", out);
  expect_refused(
      "nurbs deform " + kData + "unclamped_surface.json --uv 0.5,0.5 --to 1,2,3 -o " + out, 1,
      "unclamped_surface.json: knots_u / degree_u: not clamped", out);
  expect_refused("nurbs deform " + sheet + " --uv 0.5,0.5 --path " + kData +
                     "negative_weight_curve.json -o " + out,
                 1, "negative_weight_curve.json: weights[1]", out);
  expect_refused("nurbs deform " + sheet + " --uv 0.5,0.5 --to 1,2,3 --influence zone:" + kData +
                     "bowtie_zone.json -o " + out,
                 1, "bowtie_zone.json: polygon: not star-shaped", out);
  expect_refused("nurbs deform " + sheet + " --uv 0.5,0.5 --to 1,2,3 --influence zone:" + kData +
                     "tiny_zone.json -o " + out,
                 1, "tiny_zone.json: the zone holds no control point that influences", out);
  // ... which refinement cures.
  EXPECT_EQ(run_sculpt("nurbs deform " + sheet + " --uv 0.5,0.5 --to 1,2,3 --influence zone:" +
                       kData + "tiny_zone.json --refine 4 -o " + path("ok.json"))
                .exit_code,
            0);
  expect_refused(
      "nurbs deform " + sheet + " --uv 0.6,0.5 --path " + path("arch.json") + " -o " + out, 1,
      "arch.json: path: starts at", out);
  expect_refused("nurbs deform " + sheet + " --uv 0.5,0.5 --path " + path("arch.json") +
                     " --to 1,2,3 -o " + out,
                 1, "not at --to", out);
  expect_refused("nurbs deform " + sheet + " --uv 1.5,0.5 --to 1,2,3 -o " + out, 1,
                 "--uv 1.5,0.5: outside the domain", out);
  expect_refused("nurbs deform " + sheet + " --uv 0.5,0.5 --to 1,2,3 --refine 9 -o " + out, 1,
                 "--refine", out);
  expect_refused(
      "nurbs deform " + sheet + " --uv 0.5,0.5 --to 1,2,3 -o " + out + " --mesh " + path("m.xyz"),
      1, "m.xyz", out);
  expect_refused(
      "nurbs deform " + sheet + " --uv 0.5,0.5 --to 1,2,3 --influence gaussian:-1 -o " + out, 1,
      "gaussian:R", out);
  expect_refused("nurbs deform " + sheet + " --uv 0.5,0.5 -o " + out, 2, "--to", out);
  expect_refused("nurbs deform " + sheet + " --to 1,2,3 -o " + out, 2, "--uv", out);
  expect_refused("nurbs tessellate " + sheet + " --freeform -o " + path("f.ply"), 1, "f.ply",
                 path("f.ply"));
  // A --mesh that cannot be written leaves no -o either.
  expect_refused("nurbs deform " + sheet + " --uv 0.5,0.5 --to 1,2,3 -o " + out + " --mesh " +
                     path("missing") + "/m.ply",
                 1, "missing/m.ply", out);
  expect_refused("nurbs", 2, "subcommand", out);
}

}  // namespace
}  // namespace sculpt::station::test
