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
  p.start_stream(0);
  DeflectionIntegral after_unplug;       // the new reader's pipeline
  push(after_unplug, 1.0f, 2000, 2500);  // half a second more
  EXPECT_NEAR(p.pose().position.x, 150.0f, 1e-3);
}

// Two 3D mice at once (one in each hand): each reader's pipeline integrates
// its own deflection, so each moves the tool by its own motion, whatever
// the order their samples come in; one plugged in again restarts only its
// own stream.
TEST(PoseIntegrator, TwoDevicesEachMoveTheToolByTheirOwnMotion) {
  PoseIntegratorConfig c;
  c.max_speed = 100.0f;
  PoseIntegrator p(c);
  struct Device {
    uint32_t id;
    std::array<float, 6> axes;
    int64_t offset_ns;  // its samples' phase against the other's
    DeflectionIntegral integral = DeflectionIntegral();
  };
  Device left{1, {1.0f, 0, 0, 0, 0, 0}, 0};
  Device right{2, {0, 0.5f, 0, 0, 0, 0}, 400'000};
  auto sample = [&](Device& d, int64_t ms) {
    InputEvent e;
    e.kind = InputKind::kMotion;
    e.device_id = d.id;
    e.axes = d.axes;
    e.t_ns = ms * 1'000'000 + d.offset_ns;
    d.integral.accumulate(e);
    p.update(e);
  };
  // A second of both: the right hand's samples come 0.4 ms after the left's
  // and, every tenth, late (after the left's next one, as two readers'
  // samples may reach the station).
  for (int64_t ms = 0; ms <= 1000; ++ms) {
    sample(left, ms);
    if (ms % 10 == 9) continue;
    if (ms % 10 == 0 && ms > 0) sample(right, ms - 1);
    sample(right, ms);
  }
  EXPECT_NEAR(p.pose().position.x, 100.0f, 1e-3);  // the left's full push along x
  EXPECT_NEAR(p.pose().position.y, 50.0f, 1e-3);   // the right's half push along y
  // The right one unplugged and back: the left goes on as it was.
  p.start_stream(right.id);
  right.integral = DeflectionIntegral();
  for (int64_t ms = 1001; ms <= 1500; ++ms) {
    sample(left, ms);
    sample(right, ms);
  }
  EXPECT_NEAR(p.pose().position.x, 150.0f, 1e-3);
  // Its new stream's first sample (1001.4 ms) only set the time: 0.499 s.
  EXPECT_NEAR(p.pose().position.y, 50.0f + 50.0f * 0.499f, 1e-3);
}

// A device plugged in again gets a new id: the streams of those gone are
// forgotten, not kept one per re-plug.
TEST(PoseIntegrator, AStreamEndsWithItsDevice) {
  PoseIntegrator p;
  for (uint32_t id = 1; id <= 100; ++id) {
    p.start_stream(id);
    InputEvent e;
    e.kind = InputKind::kMotion;
    e.device_id = id;
    e.t_ns = int64_t{id} * 1'000'000;
    p.update(e);
    EXPECT_EQ(p.stream_count(), 1u);
    p.end_stream(id);
  }
  EXPECT_EQ(p.stream_count(), 0u);
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
