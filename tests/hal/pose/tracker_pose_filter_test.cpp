// The one-euro filter on a tracker's pose: a held tracker's jitter is
// smoothed, a turn is followed by the short way round, and nothing lags for
// ever.

#include "sculpt/hal/pose/tracker_pose_filter.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sculpt/hal/parsers/opentrack_datagram.h"
#include "sculpt/hal/pose/pose_integrator.h"

namespace sculpt::hal {
namespace {

constexpr int64_t kPeriodNs = 4'000'000;  // a 250 Hz tracker

TrackerPose pose(double x_mm, std::array<double, 4> q = {1, 0, 0, 0}) {
  TrackerPose p;
  p.position_mm = {x_mm, 0, 0};
  p.quat_wxyz = q;
  return p;
}

double angle_between(const std::array<double, 4>& a, const std::array<double, 4>& b) {
  const double dot = std::fabs(a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]);
  return 2.0 * std::acos(std::min(1.0, dot));
}

TEST(TrackerPoseFilter, AHeldTrackersJitterIsSmoothed) {
  TrackerPoseFilter f;
  double worst_mm = 0;
  for (int i = 0; i < 500; ++i) {
    const double jitter_mm = (i % 2 == 0) ? 0.5 : -0.5;
    const TrackerPose out = f.filter(pose(100.0 + jitter_mm), i * kPeriodNs);
    if (i > 50) worst_mm = std::max(worst_mm, std::fabs(out.position_mm[0] - 100.0));
  }
  EXPECT_LT(worst_mm, 0.1) << "a still hand stays still";
}

TEST(TrackerPoseFilter, OrientationFollowsATurnTheShortWayAndArrives) {
  TrackerPoseFilter f;
  const auto start = quat_from_yaw_pitch_roll_deg(170, 0, 0);
  auto target = quat_from_yaw_pitch_roll_deg(-170, 0, 0);  // 20 degrees on, across ±180
  for (double& c : target)
    c = -c;  // the same rotation, its other sign: must not make the filter go round
  f.filter(pose(0, start), 0);
  double largest_step = 0;
  std::array<double, 4> prev = start;
  TrackerPose out;
  for (int i = 1; i <= 1000; ++i) {
    out = f.filter(pose(0, target), i * kPeriodNs);
    largest_step = std::max(largest_step, angle_between(prev, out.quat_wxyz));
    prev = out.quat_wxyz;
  }
  EXPECT_LT(largest_step, 20.0 * M_PI / 180.0) << "smoothed, not a jump";
  EXPECT_LT(angle_between(out.quat_wxyz, target), 1e-3) << "four seconds on, it has arrived";
  EXPECT_TRUE(is_finite_unit_pose(out, 1e-9));
}

TEST(TrackerPoseFilter, TheFirstSampleAfterResetPassesUnchanged) {
  TrackerPoseFilter f;
  f.filter(pose(0), 0);
  f.filter(pose(10), kPeriodNs);
  f.reset();
  EXPECT_EQ(f.filter(pose(500), 2 * kPeriodNs).position_mm[0], 500.0);
  TrackerFilterParams off;
  off.enabled = false;
  TrackerPoseFilter none(off);
  none.filter(pose(0), 0);
  EXPECT_EQ(none.filter(pose(10), kPeriodNs).position_mm[0], 10.0);
}

TEST(TrackerPoseFilter, AnOverflowingJumpRestartsTheFilterInsteadOfHoldingNaN) {
  TrackerPoseFilter f;
  f.filter(pose(-1e300), 0);
  f.filter(pose(1e300), kPeriodNs);  // a speed beyond double
  const TrackerPose out = f.filter(pose(5), 2 * kPeriodNs);
  EXPECT_TRUE(is_finite_unit_pose(out, 1e-9));
  const TrackerPose later = f.filter(pose(5), 3 * kPeriodNs);
  EXPECT_TRUE(is_finite_unit_pose(later, 1e-9));
}

TEST(TrackerPoseFilter, ThePoseIntegratorSmoothsTrackerPosesAndStillNeverJumps) {
  ToolPose start;
  start.position = {64, 64, 64};
  PoseIntegrator p({}, start);  // the filter on, as by default
  InputEvent e;
  e.kind = InputKind::kMotion;
  e.absolute = true;
  e.has_pose = true;
  float prev_x = 64.0f;
  for (int i = 0; i < 200; ++i) {
    e.pose = pose((i % 2 == 0) ? 300.5 : 299.5);  // 1 mm of jitter, far from the origin
    e.t_ns = (i + 1) * kPeriodNs;
    p.update(e);
    EXPECT_NEAR(p.pose().position.x, 64.0f, 1.0f) << "sample " << i;
    EXPECT_LT(std::fabs(p.pose().position.x - prev_x), 0.2f) << "sample " << i;
    prev_x = p.pose().position.x;
  }
}

}  // namespace
}  // namespace sculpt::hal
