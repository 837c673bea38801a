#include "sculpt/hal/stroke/stroke_sampler.h"

#include <cmath>

#include <gtest/gtest.h>

#include "sculpt/hal/pose/deflection_integral.h"
#include "sculpt/hal/pose/pose_integrator.h"

namespace sculpt::hal {
namespace {

// A 3D mouse pushed right for 1 s while twisting, sampled at rate_hz, through
// the real integrator and sampler.
std::vector<Dab> stroke_at(int rate_hz) {
  PoseIntegratorConfig c;
  c.max_speed = 101.0f;  // 101 units in 1 s: the last dab (at 100) is not on the edge
  PoseIntegrator integrator(c);
  DeflectionIntegral integral;
  StrokeSampler sampler(/*tool_size=*/8.0f, /*spacing_fraction=*/0.25f);
  std::vector<Dab> dabs;
  const int64_t period = 1'000'000'000 / rate_hz;
  for (int64_t i = 0; i <= rate_hz; ++i) {
    InputEvent e;
    e.kind = InputKind::kMotion;
    e.t_ns = i * period;
    e.axes = {1.0f, 0, 0, 0, 0, 0.5f};
    integral.accumulate(e);
    const ToolPose& pose = integrator.update(e);
    if (i == 0) {
      sampler.begin(pose, dabs);
    } else {
      sampler.add(pose, dabs);
    }
  }
  sampler.end();
  return dabs;
}

TEST(StrokeSampler, DabsDependOnThePathNotOnTheReportRate) {
  const std::vector<Dab> slow = stroke_at(125);
  const std::vector<Dab> fast = stroke_at(1000);
  // 101 units at a spacing of 2: the start plus 50.
  ASSERT_EQ(slow.size(), 51u);
  ASSERT_EQ(fast.size(), slow.size());
  for (size_t i = 0; i < slow.size(); ++i) {
    EXPECT_EQ(slow[i].index, static_cast<int64_t>(i));
    EXPECT_NEAR(slow[i].position.x, 2.0f * static_cast<float>(i), 1e-3);
    EXPECT_NEAR(fast[i].position.x, slow[i].position.x, 1e-3);
    EXPECT_NEAR(std::abs(glm::dot(fast[i].orientation, slow[i].orientation)), 1.0f, 1e-5);
    EXPECT_NEAR(static_cast<double>(fast[i].t_ns), static_cast<double>(slow[i].t_ns), 1e3);
  }
  // Time follows distance at constant speed: dab 25 (50 units) at 50/101 s.
  EXPECT_NEAR(static_cast<double>(fast[25].t_ns), 50.0 / 101.0 * 1e9, 1e3);
}

TEST(StrokeSampler, OrientationIsSlerpedBetweenPoses) {
  StrokeSampler s(4.0f, 0.5f);  // spacing 2
  std::vector<Dab> dabs;
  ToolPose a;
  ToolPose b;
  b.position = glm::vec3(4, 0, 0);
  b.orientation = glm::angleAxis(3.14159265f / 2, glm::vec3(0, 0, 1));
  b.t_ns = 1000;
  s.begin(a, dabs);
  s.add(b, dabs);
  ASSERT_EQ(dabs.size(), 3u);
  const float angle = glm::angle(dabs[1].orientation);
  EXPECT_NEAR(angle, 3.14159265f / 4, 1e-4);
  EXPECT_EQ(dabs[1].t_ns, 500);
}

TEST(StrokeSampler, EndClosesWithoutExtraDabsAndAddAfterEndIsIgnored) {
  StrokeSampler s(4.0f, 0.5f);
  std::vector<Dab> dabs;
  ToolPose p;
  s.begin(p, dabs);
  p.position.x = 3.0f;
  s.add(p, dabs);
  EXPECT_EQ(dabs.size(), 2u);
  s.end();
  EXPECT_FALSE(s.active());
  p.position.x = 10.0f;
  s.add(p, dabs);
  EXPECT_EQ(dabs.size(), 2u);
}

}  // namespace
}  // namespace sculpt::hal
