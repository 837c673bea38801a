#include "sculpt/station/view/orbit_camera.h"

#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

namespace sculpt::station {
namespace {

void expect_near(glm::vec3 a, glm::vec3 b, float tol = 1e-3f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(OrbitCamera, FramesTheBlockSoEveryCornerIsInView) {
  OrbitCamera c;
  c.frame(glm::vec3(0.0f), glm::vec3(256.0f));
  expect_near(c.target(), glm::vec3(128.0f));
  const glm::mat4 vp = c.projection(1.0f) * c.view();
  for (int i = 0; i < 8; ++i) {
    const glm::vec4 p = vp * glm::vec4((i & 1) ? 256.0f : 0.0f, (i & 2) ? 256.0f : 0.0f,
                                       (i & 4) ? 256.0f : 0.0f, 1.0f);
    EXPECT_LT(std::abs(p.x / p.w), 1.0f) << i;
    EXPECT_LT(std::abs(p.y / p.w), 1.0f) << i;
  }
}

TEST(OrbitCamera, OrbitKeepsTheDistanceAndNeverFlips) {
  OrbitCamera c;
  c.frame(glm::vec3(0.0f), glm::vec3(100.0f));
  const float d = c.distance();
  c.orbit(1.0f, 10.0f);  // far past the pole
  EXPECT_NEAR(glm::length(c.eye() - c.target()), d, 1e-2f);
  EXPECT_LT(c.pitch(), 1.56f);
  EXPECT_GT(glm::dot(c.up(), glm::vec3(0, 1, 0)), 0.0f);
  // The view basis stays orthonormal.
  EXPECT_NEAR(glm::dot(c.right(), c.forward()), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::dot(c.up(), c.forward()), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(c.up()), 1.0f, 1e-5f);
}

TEST(OrbitCamera, PanMovesTargetAndEyeTogetherInTheViewPlane) {
  OrbitCamera c;
  c.set(glm::vec3(0.0f), 0.0f, 0.0f, 100.0f);
  const glm::vec3 eye = c.eye();
  c.pan(glm::vec2(100.0f, 0.0f), 1000.0f);
  const glm::vec3 moved = c.target();
  EXPECT_NEAR(glm::dot(moved, c.forward()), 0.0f, 1e-4f);  // in the view plane
  EXPECT_LT(moved.x, 0.0f);  // dragging right moves the scene right: the target goes left
  expect_near(c.eye() - eye, moved);
}

TEST(OrbitCamera, ZoomScalesTheDistanceWithinLimits) {
  OrbitCamera c;
  c.set(glm::vec3(0.0f), 0.0f, 0.0f, 100.0f);
  c.zoom(0.5f);
  EXPECT_FLOAT_EQ(c.distance(), 50.0f);
  c.zoom(0.0f);  // ignored
  c.zoom(-3.0f);
  EXPECT_FLOAT_EQ(c.distance(), 50.0f);
  c.zoom(1e-9f);
  EXPECT_GE(c.distance(), 1.0f);
}

TEST(OrbitCamera, CentreRayGoesThroughTheTarget) {
  OrbitCamera c;
  c.frame(glm::vec3(0.0f), glm::vec3(64.0f));
  const Ray r = c.ray(glm::vec2(0.0f), 1.5f);
  expect_near(r.origin, c.eye());
  const glm::vec3 to_target = glm::normalize(c.target() - c.eye());
  expect_near(r.direction, to_target, 1e-5f);
  // A ray through the right edge leaves at half the horizontal field of view.
  const Ray edge = c.ray(glm::vec2(1.0f, 0.0f), 1.0f);
  EXPECT_NEAR(std::acos(glm::dot(edge.direction, to_target)), 0.5f * OrbitCamera::kFovY, 1e-4f);
}

}  // namespace
}  // namespace sculpt::station
