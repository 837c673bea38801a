// Tracker poses into the sculpture: the tool follows the tracker's motion
// from wherever it was, scaled and turned by the calibration, and never
// jumps when a tracker is first seen or found again.

#include "sculpt/hal/pose/tracker_mapping.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sculpt/hal/pose/pose_integrator.h"

namespace sculpt::hal {
namespace {

TrackerPose at(double x, double y, double z, std::array<double, 4> q = {1, 0, 0, 0}) {
  TrackerPose p;
  p.position_mm = {x, y, z};
  p.quat_wxyz = q;
  return p;
}

InputEvent pose_event(const TrackerPose& p, int64_t t_ns) {
  InputEvent e;
  e.kind = InputKind::kMotion;
  e.absolute = true;
  e.has_pose = true;
  e.pose = p;
  e.t_ns = t_ns;
  return e;
}

TEST(TrackerMapping, TheFirstPoseMapsToTheToolAndLaterOnesMoveItByScale) {
  TrackerCalibration c;
  c.scale_vox_per_mm = 0.5;
  TrackerMapping m(c);
  ToolPose tool;
  tool.position = {10, 20, 30};
  tool = m.map(at(500, 500, 500), tool);  // far from the tracker's origin: no jump
  EXPECT_EQ(tool.position, glm::vec3(10, 20, 30));
  tool = m.map(at(510, 480, 500), tool);
  EXPECT_FLOAT_EQ(tool.position.x, 15.0f);
  EXPECT_FLOAT_EQ(tool.position.y, 10.0f);
  EXPECT_FLOAT_EQ(tool.position.z, 30.0f);
}

TEST(TrackerMapping, OrientationIsTheTrackersTurnSinceTheAnchorInTheSculpturesAxes) {
  TrackerCalibration c;
  // The tracker's +X is the sculpture's +Z (a quarter turn about +Y).
  c.tracker_to_sculpture = glm::angleAxis(glm::half_pi<double>(), glm::dvec3(0, 1, 0));
  TrackerMapping m(c);
  ToolPose tool;
  const double h = std::sqrt(0.5);
  tool = m.map(at(0, 0, 0, {h, h, 0, 0}), tool);  // held turned: still no jump
  EXPECT_NEAR(tool.orientation.w, 1.0f, 1e-6);
  tool = m.map(at(10, 0, 0, {h, h, 0, 0}), tool);
  EXPECT_NEAR(tool.position.z, -10.0f, 1e-4);  // R(+90 about Y) takes +X to -Z
  EXPECT_NEAR(tool.position.x, 0.0f, 1e-4);
  // A quarter turn about the tracker's +Z, on top of the held one.
  const glm::dquat held(h, h, 0, 0);
  const glm::dquat more = glm::angleAxis(glm::half_pi<double>(), glm::dvec3(0, 0, 1)) * held;
  tool = m.map(at(10, 0, 0, {more.w, more.x, more.y, more.z}), tool);
  // About the tracker's Z is about the sculpture's +X after R.
  const glm::vec3 axis = glm::axis(tool.orientation);
  EXPECT_NEAR(glm::angle(tool.orientation), glm::half_pi<float>(), 1e-5);
  EXPECT_NEAR(axis.x, 1.0f, 1e-5);
}

TEST(TrackerMapping, AnotherSensorDoesNotMoveTheTool) {
  TrackerMapping m;
  ToolPose tool;
  TrackerPose a = at(0, 0, 0);
  tool = m.map(a, tool);
  TrackerPose b = at(100, 0, 0);
  b.sensor = 1;
  tool = m.map(b, tool);
  EXPECT_EQ(tool.position, glm::vec3(0));
}

TEST(TrackerMapping, APoseBeyondFloatRangeMovesNothing) {
  TrackerMapping m;
  ToolPose tool;
  tool.position = {1, 2, 3};
  tool = m.map(at(-1e300, 0, 0), tool);
  tool = m.map(at(1e300, 0, 0), tool);  // the difference overflows to infinity
  EXPECT_EQ(tool.position, glm::vec3(1, 2, 3));
  tool = m.map(at(-1e300, 0, 0), tool);
  EXPECT_EQ(tool.position, glm::vec3(1, 2, 3));
}

TEST(TrackerMapping, PoseIntegratorReanchorsAfterTrackingIsLost) {
  ToolPose start;
  start.position = {128, 128, 128};
  PoseIntegratorConfig config;
  config.tracker_filter.enabled = false;  // exact positions
  PoseIntegrator p(config, start);
  p.update(pose_event(at(0, 0, 0), 1));
  EXPECT_EQ(p.pose().position, glm::vec3(128));
  p.update(pose_event(at(10, 0, 0), 2));
  EXPECT_FLOAT_EQ(p.pose().position.x, 138.0f);
  p.lose_tracking();
  // Found again 300 mm away: the tool stays, then follows from there.
  p.update(pose_event(at(310, 0, 0), 3));
  EXPECT_FLOAT_EQ(p.pose().position.x, 138.0f);
  EXPECT_EQ(p.pose().t_ns, 3);
  p.update(pose_event(at(315, 0, 0), 4));
  EXPECT_FLOAT_EQ(p.pose().position.x, 143.0f);
  // A tool put elsewhere (a tool_pose command) re-anchors too.
  ToolPose moved;
  moved.position = {5, 5, 5};
  p.reset(moved);
  p.update(pose_event(at(0, 0, 0), 5));
  EXPECT_EQ(p.pose().position, glm::vec3(5));
}

}  // namespace
}  // namespace sculpt::hal
