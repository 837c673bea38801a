#include "sculpt/core/nurbs/nurbs_json.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "nurbs_fixtures.h"
#include "scratch_dir.h"
#include "sculpt/core/nurbs/nurbs_obj.h"

namespace sculpt::core::nurbs {
namespace {

std::string error_of(const std::string& text) {
  Result<NurbsSurface> r = parse_surface_json(text);
  return r.ok() ? "" : r.error().message();
}

TEST(NurbsJson, SurfaceCurveAndZoneRoundTripExactly) {
  sculpt::test::ScratchDir dir;
  NurbsSurface s = test::quarter_cylinder(3.0, 5.0);
  s.points[4].x = 0.1 + 1e-17;  // any double survives
  ASSERT_TRUE(write_json(dir.path() / "s.json", s).ok());
  Result<NurbsSurface> back = read_surface_json(dir.path() / "s.json");
  ASSERT_TRUE(back.ok()) << back.error().message();
  EXPECT_EQ(back->points, s.points);
  EXPECT_EQ(back->weights, s.weights);
  EXPECT_EQ(back->knots_u, s.knots_u);
  EXPECT_EQ(back->knots_v, s.knots_v);

  const NurbsCurve c = test::quarter_circle(2.5);
  ASSERT_TRUE(write_json(dir.path() / "c.json", c).ok());
  Result<NurbsCurve> cb = read_curve_json(dir.path() / "c.json");
  ASSERT_TRUE(cb.ok());
  EXPECT_EQ(cb->points, c.points);
  EXPECT_EQ(cb->weights, c.weights);

  ParameterZone z;
  z.shape = ParameterZone::Shape::kPolygon;
  z.polygon = {{0.1, 0.1}, {0.9, 0.2}, {0.5, 0.8}};
  ASSERT_TRUE(write_json(dir.path() / "z.json", z).ok());
  Result<ParameterZone> zb = read_zone_json(dir.path() / "z.json");
  ASSERT_TRUE(zb.ok());
  EXPECT_EQ(zb->polygon, z.polygon);
}

TEST(NurbsJson, BadFilesNameTheFieldAndTheFile) {
  const std::string good = to_json(example_sheet());
  EXPECT_EQ(error_of(good), "");
  EXPECT_NE(error_of("{").find("not valid JSON"), std::string::npos);
  EXPECT_NE(error_of("[1]").find("expected a JSON object"), std::string::npos);
  // A number beyond a double (found by fuzzing: it ended the process).
  EXPECT_NE(error_of("{\"degree_u\": 1e400}").find("out of range for a double"), std::string::npos);
  std::string t = good;
  t.replace(t.find("\"count_u\": 15"), 13, "\"count_u\": 14");
  EXPECT_NE(error_of(t).find("knots_u"), std::string::npos) << error_of(t);
  t = good;
  t.replace(t.find("\"degree_v\": 3"), 13, "\"degree_v\": \"3\"");
  EXPECT_NE(error_of(t).find("\"degree_v\" must be an integer"), std::string::npos);
  t = good;
  t.replace(t.find("\"type\": \"nurbs_surface\""), 23, "\"type\": \"nurbs_curve\"");
  EXPECT_NE(error_of(t).find("\"type\" must be \"nurbs_surface\""), std::string::npos);
  t = good;
  const size_t first_point = t.find("[", t.find("\"control_points\"") + 20);
  t.replace(first_point, 1, "[1, ");
  EXPECT_NE(error_of(t).find("control_points[0]: expected 3 numbers"), std::string::npos);
  EXPECT_NE(error_of(R"({"degree_u": 1})").find("missing \"degree_v\""), std::string::npos);
  EXPECT_NE(parse_zone_json(R"({"shape": "square"})").error().message().find("\"shape\""),
            std::string::npos);
  EXPECT_NE(parse_zone_json(R"({"shape": "circle", "centre": [0.5, 0.5], "radius": -1})")
                .error()
                .message()
                .find("radius"),
            std::string::npos);
  EXPECT_NE(
      parse_curve_json(
          R"({"degree": 2, "knots": [0,0,0,1,1,1], "control_points": [[0,0,0],[1,0,0],[1,1,0]], "weights": [1, 0, 1]})")
          .error()
          .message()
          .find("weights[1]"),
      std::string::npos);

  sculpt::test::ScratchDir dir;
  Result<NurbsSurface> missing = read_surface_json(dir.path() / "none.json");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message().find("none.json: cannot open"), std::string::npos);
  std::ofstream(dir.path() / "bad.json") << "{\"degree_u\": 3}";
  Result<NurbsSurface> bad = read_surface_json(dir.path() / "bad.json");
  EXPECT_NE(bad.error().message().find("bad.json: missing"), std::string::npos);
}

// Reproducer from the hardening review: weights of 1e308 passed as finite,
// the homogeneous points overflowed and `nurbs deform` wrote NaN that this
// reader then refused. Weights and coordinates are now bounded where read,
// and a writer refuses what the reader would.
TEST(NurbsJson, WeightsAndCoordinatesAreBoundedAndNeverWrittenNonFinite) {
  const std::string huge_weight =
      R"({"degree": 2, "knots": [0,0,0,1,1,1], "control_points": [[0,0,0],[1,0,0],[1,1,0]], "weights": [1, 1e308, 1]})";
  EXPECT_NE(parse_curve_json(huge_weight).error().message().find("weights[1] = 1e+308 is not in"),
            std::string::npos);
  const std::string far_point =
      R"({"degree": 1, "knots": [0,0,1,1], "control_points": [[0,0,0],[2e9,0,0]]})";
  EXPECT_NE(parse_curve_json(far_point).error().message().find("control_points[1]"),
            std::string::npos);
  // At the limits, evaluation stays finite.
  const std::string at_limits =
      R"({"degree": 1, "knots": [0,0,1,1], "control_points": [[1e9,-1e9,1e9],[-1e9,1e9,-1e9]], "weights": [1e9, 1e-9]})";
  Result<NurbsCurve> c = parse_curve_json(at_limits);
  ASSERT_TRUE(c.ok()) << c.error().message();
  for (double t : {0.0, 1e-12, 0.5, 1.0}) {
    const glm::dvec3 p = evaluate(*c, t);
    EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << t;
  }

  sculpt::test::ScratchDir dir;
  NurbsCurve nan_curve = *c;
  nan_curve.points[0].x = std::nan("");
  const Status written = write_json(dir.path() / "nan.json", nan_curve);
  ASSERT_FALSE(written.ok());
  EXPECT_NE(written.error().message().find("nan.json: not written: control_points[0]"),
            std::string::npos)
      << written.error().message();
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "nan.json"));
}

TEST(NurbsObj, FreeFormSurfaceAndCurve) {
  const std::string rat = to_freeform_obj(test::quarter_cylinder(1.0, 2.0));
  EXPECT_NE(rat.find("cstype rat bspline\ndeg 2 3\nsurf 0 1 0 1 1 2 3 4"), std::string::npos)
      << rat;
  EXPECT_NE(rat.find("v 1 1 0 0.70710678118654757\n"), std::string::npos) << rat;
  EXPECT_NE(rat.find("parm u 0 0 0 1 1 1\n"), std::string::npos);
  EXPECT_NE(rat.find("\nend\n"), std::string::npos);
  const std::string poly = to_freeform_obj(example_sheet());
  EXPECT_NE(poly.find("cstype bspline\ndeg 3 3\n"), std::string::npos);
  EXPECT_NE(poly.find(" 150\nparm u"), std::string::npos);
  const std::string curve = to_freeform_obj(test::quarter_circle(1.0));
  EXPECT_NE(curve.find("cstype rat bspline\ndeg 2\ncurv 0 1 1 2 3\nparm u 0 0 0 1 1 1\nend\n"),
            std::string::npos)
      << curve;
}

}  // namespace
}  // namespace sculpt::core::nurbs
