// Tracker poses into the sculpture: the tool follows the tracker's motion
// from wherever it was, scaled and turned by the calibration, and never
// jumps when a tracker is first seen or found again.

#include "sculpt/hal/pose/tracker_mapping.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sculpt/hal/pose/deflection_integral.h"
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

namespace sculpt::hal {
namespace {

PoseIntegrator exact_tracker_integrator(glm::vec3 start_vox) {
  ToolPose start;
  start.position = start_vox;
  PoseIntegratorConfig config;
  config.tracker_filter.enabled = false;  // exact positions
  return PoseIntegrator(config, start);
}

TEST(TrackerClutch, WhileHeldTheToolStaysAndLettingGoReanchorsWhereItIs) {
  PoseIntegrator p = exact_tracker_integrator({100, 100, 100});
  p.update(pose_event(at(0, 0, 0), 1));
  p.update(pose_event(at(20, 0, 0), 2));
  EXPECT_FLOAT_EQ(p.pose().position.x, 120.0f);
  // The hand moves back 50 mm with the clutch held: the tool does not.
  p.set_clutch(true);
  EXPECT_TRUE(p.clutched());
  p.update(pose_event(at(-30, 0, 0), 3));
  EXPECT_FLOAT_EQ(p.pose().position.x, 120.0f);
  EXPECT_EQ(p.pose().t_ns, 3);  // time moves on
  p.set_clutch(false);
  // Let go: the hand's pose there is the tool's, and motion goes on from it.
  p.update(pose_event(at(-30, 0, 0), 4));
  EXPECT_FLOAT_EQ(p.pose().position.x, 120.0f);
  p.update(pose_event(at(-20, 0, 0), 5));
  EXPECT_FLOAT_EQ(p.pose().position.x, 130.0f);
}

TEST(TrackerClutch, ARateControlledMouseMovesNothingWhileHeldNorAfterForIt) {
  DeflectionIntegral integral;  // as MotionPipeline hands samples over
  auto motion = [&](std::array<float, 6> axes, int64_t t_ns) {
    InputEvent e;
    e.kind = InputKind::kMotion;
    e.axes = axes;
    e.t_ns = t_ns;
    integral.accumulate(e);
    return e;
  };
  PoseIntegratorConfig config;
  config.max_speed = 100.0f;
  PoseIntegrator p(config);
  p.update(motion({1, 0, 0, 0, 0, 0}, 0));
  p.set_clutch(true);
  constexpr int64_t kPeriodNs = 10'000'000;  // a 100 Hz mouse
  for (int64_t i = 1; i <= 100; ++i)
    p.update(motion({1, 0, 0, 0, 0, 0}, i * kPeriodNs));  // a second pushed, held
  EXPECT_FLOAT_EQ(p.pose().position.x, 0.0f);
  p.set_clutch(false);
  for (int64_t i = 101; i <= 110; ++i)
    p.update(motion({1, 0, 0, 0, 0, 0}, i * kPeriodNs));
  // Only the tenth of a second after letting go moved it.
  EXPECT_NEAR(p.pose().position.x, 10.0f, 1e-3f);
}

TEST(TrackerCalibration, ANewCalibrationReanchorsAndScalesWhatFollows) {
  PoseIntegrator p = exact_tracker_integrator({0, 0, 0});
  p.update(pose_event(at(0, 0, 0), 1));
  p.update(pose_event(at(10, 0, 0), 2));
  EXPECT_FLOAT_EQ(p.pose().position.x, 10.0f);
  TrackerCalibration c;
  c.scale_vox_per_mm = 2.0;
  c.tracker_to_sculpture = glm::angleAxis(glm::half_pi<double>(), glm::dvec3(0, 0, 1));
  p.calibrate_tracker(c);
  EXPECT_EQ(p.tracker_calibration().scale_vox_per_mm, 2.0);
  p.update(pose_event(at(10, 0, 0), 3));  // anchors: no jump
  EXPECT_FLOAT_EQ(p.pose().position.x, 10.0f);
  p.update(pose_event(at(15, 0, 0), 4));  // +5 mm on the tracker's x: +10 voxels on y
  EXPECT_NEAR(p.pose().position.x, 10.0f, 1e-4f);
  EXPECT_NEAR(p.pose().position.y, 10.0f, 1e-4f);
}

}  // namespace
}  // namespace sculpt::hal
