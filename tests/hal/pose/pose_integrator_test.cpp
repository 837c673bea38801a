#include "sculpt/hal/pose/pose_integrator.h"

#include "sculpt/hal/pose/deflection_integral.h"

#include <cmath>

#include <gtest/gtest.h>

namespace sculpt::hal {
namespace {

// Samples as MotionPipeline hands them over: with the deflection integral.
InputEvent motion(std::array<float, 6> axes, int64_t t_ns, bool absolute = false) {
  static DeflectionIntegral integral;
  if (t_ns == 0) integral.reset();
  InputEvent e;
  e.kind = InputKind::kMotion;
  e.axes = axes;
  e.t_ns = t_ns;
  e.absolute = absolute;
  integral.accumulate(e);
  return e;
}

ToolPose push_for_one_second(int rate_hz, std::array<float, 6> axes) {
  PoseIntegratorConfig c;
  c.max_speed = 100.0f;
  PoseIntegrator p(c);
  const int64_t period = 1'000'000'000 / rate_hz;
  for (int64_t i = 0; i <= rate_hz; ++i)
    p.update(motion(axes, i * period));
  return p.pose();
}

TEST(PoseIntegrator, RateControlIntegratesOverSampleTimesNotSampleCount) {
  const ToolPose slow = push_for_one_second(125, {0.5f, 0, -1.0f, 0, 0, 0});
  const ToolPose fast = push_for_one_second(1000, {0.5f, 0, -1.0f, 0, 0, 0});
  EXPECT_NEAR(slow.position.x, 50.0f, 1e-3);
  EXPECT_NEAR(slow.position.z, -100.0f, 1e-3);
  EXPECT_NEAR(fast.position.x, slow.position.x, 1e-3);
  EXPECT_EQ(fast.t_ns, 1'000'000'000);
}

TEST(PoseIntegrator, TwistTurnsAtAngularSpeedAndStaysUnit) {
  PoseIntegratorConfig c;
  c.max_angular_speed = 3.14159265f / 2;
  PoseIntegrator p(c);
  for (int64_t i = 0; i <= 1000; ++i)
    p.update(motion({0, 0, 0, 0, 1.0f, 0}, i * 1'000'000));
  const glm::quat q = p.pose().orientation;
  EXPECT_NEAR(glm::length(q), 1.0f, 1e-5);
  const glm::vec3 x = q * glm::vec3(1, 0, 0);  // a quarter turn about +Y sends +X to -Z
  EXPECT_NEAR(x.z, -1.0f, 1e-3);
}

TEST(PoseIntegrator, GapIsCappedAndOldSamplesIgnored) {
  PoseIntegratorConfig c;
  c.max_speed = 100.0f;
  PoseIntegrator p(c);  // DeflectionIntegral holds a deflection for 50 ms at most
  p.update(motion({1, 0, 0, 0, 0, 0}, 0));
  p.update(motion({1, 0, 0, 0, 0, 0}, 2'000'000'000));  // a 2 s stall
  EXPECT_NEAR(p.pose().position.x, 5.0f, 1e-4);
  p.update(motion({1, 0, 0, 0, 0, 0}, 1'000'000'000));  // out of order
  EXPECT_NEAR(p.pose().position.x, 5.0f, 1e-4);
}

// A device unplugged and plugged back in reports through a new pipeline,
// whose integral starts from zero again: the tool goes on from where it was,
// not thrown back by the old stream's integral.
TEST(PoseIntegrator, ADeviceBackFromAnUnplugGoesOnFromWhereTheToolIs) {
  PoseIntegratorConfig c;
  c.max_speed = 100.0f;
  PoseIntegrator p(c);
  auto push = [&](DeflectionIntegral& stream, float tx, int64_t from_ms, int64_t to_ms) {
    for (int64_t ms = from_ms; ms <= to_ms; ++ms) {
      InputEvent e;
      e.kind = InputKind::kMotion;
      e.axes = {tx, 0, 0, 0, 0, 0};
      e.t_ns = ms * 1'000'000;
      stream.accumulate(e);
      p.update(e);
    }
  };
  DeflectionIntegral before_unplug;
  push(before_unplug, 1.0f, 0, 1000);  // a second at full push: 100 along x
  EXPECT_NEAR(p.pose().position.x, 100.0f, 1e-3);
  p.start_stream();
  DeflectionIntegral after_unplug;       // the new reader's pipeline
  push(after_unplug, 1.0f, 2000, 2500);  // half a second more
  EXPECT_NEAR(p.pose().position.x, 150.0f, 1e-3);
}

TEST(PoseIntegrator, PositionControlMapsTheWorkspace) {
  PoseIntegratorConfig c;
  c.workspace_center = glm::vec3(10, 20, 30);
  c.workspace_half_extent = 5.0f;
  PoseIntegrator p(c);
  p.update(motion({1.0f, -0.5f, 0, 0, 0, 0.5f}, 42, /*absolute=*/true));
  EXPECT_NEAR(p.pose().position.x, 15.0f, 1e-5);
  EXPECT_NEAR(p.pose().position.y, 17.5f, 1e-5);
  const glm::vec3 x = p.pose().orientation * glm::vec3(1, 0, 0);  // half of pi about +Z
  EXPECT_NEAR(x.y, 1.0f, 1e-5);
  EXPECT_EQ(p.pose().t_ns, 42);
}

}  // namespace
}  // namespace sculpt::hal
