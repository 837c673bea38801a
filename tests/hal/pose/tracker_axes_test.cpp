// Tracker axes as a user names them: a rotation, or one clear error.

#include "sculpt/hal/pose/tracker_axes.h"

#include <gtest/gtest.h>

namespace sculpt::hal {
namespace {

glm::dvec3 turn(std::string_view spec, glm::dvec3 v) {
  const Result<glm::dquat> q = parse_tracker_axes(spec);
  EXPECT_TRUE(q.ok()) << (q.ok() ? "" : q.error().message());
  return q.ok() ? q.value() * v : glm::dvec3(0.0);
}

void expect_near(glm::dvec3 a, glm::dvec3 b) {
  EXPECT_NEAR(a.x, b.x, 1e-12);
  EXPECT_NEAR(a.y, b.y, 1e-12);
  EXPECT_NEAR(a.z, b.z, 1e-12);
}

TEST(TrackerAxes, EachSculptureAxisTakesTheNamedTrackerAxis) {
  expect_near(turn("x,y,z", {1, 2, 3}), {1, 2, 3});
  // Sculpture x = tracker x, y = tracker z, z = -tracker y (a z-up tracker).
  expect_near(turn("x,z,-y", {1, 2, 3}), {1, 3, -2});
  expect_near(turn("-x,y,-z", {1, 2, 3}), {-1, 2, -3});
  expect_near(turn("y,z,x", {1, 2, 3}), {2, 3, 1});
  expect_near(turn("+z,-y,+x", {1, 2, 3}), {3, -2, 1});
}

TEST(TrackerAxes, WhatIsNotARotationIsRefusedWithTheReason) {
  const auto why = [](std::string_view spec) {
    const Result<glm::dquat> q = parse_tracker_axes(spec);
    return q.ok() ? std::string("accepted") : q.error().message();
  };
  EXPECT_NE(why("y,x,z").find("mirror image"), std::string::npos) << why("y,x,z");
  EXPECT_NE(why("x,y,-z").find("mirror image"), std::string::npos);
  EXPECT_NE(why("x,y").find("fewer than three"), std::string::npos);
  EXPECT_NE(why("x,y,z,x").find("more than three"), std::string::npos);
  EXPECT_NE(why("x,x,z").find("x is named twice"), std::string::npos);
  EXPECT_NE(why("x,w,z").find("\"w\" is not an axis"), std::string::npos);
  EXPECT_NE(why("x,,z").find("\"\" is not an axis"), std::string::npos);
  EXPECT_NE(why("").find("fewer than three"), std::string::npos);
  EXPECT_NE(why("x,y,z").find("accepted"), std::string::npos);
  // The message names the input.
  EXPECT_NE(why("x,y").find("tracker axes \"x,y\""), std::string::npos);
}

}  // namespace
}  // namespace sculpt::hal
