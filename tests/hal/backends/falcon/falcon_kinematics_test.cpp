// The Falcon's delta kinematics over its whole workspace (a 5 mm grid of
// points within the 40 mm radius of the force limits table): position ->
// encoders -> position, the Jacobian against finite differences of the
// inverse, and forces to motor commands (direction, clamping, int16 range).

#include "backends/falcon/falcon_kinematics.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

namespace sculpt::hal::falcon {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<glm::dvec3> workspace_grid(double step_mm = 5.0, double radius_mm = 40.0) {
  std::vector<glm::dvec3> out;
  const int n = static_cast<int>(radius_mm / step_mm);
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j)
      for (int k = -n; k <= n; ++k) {
        const glm::dvec3 p(i * step_mm, j * step_mm, k * step_mm);
        if (glm::length(p) <= radius_mm + 1e-9) out.push_back(p);
      }
  return out;
}

TEST(FalconKinematics, EncoderScaleIsTheCapstanOverTheSector) {
  // 1280 counts per motor turn; the thigh turns 14.25 / 110 of that.
  EXPECT_NEAR(falcon_rad_per_count(), 2 * kPi * 14.25 / 110.0 / 1280.0, 1e-15);
  EXPECT_NEAR(falcon_angle_at_zero_count_rad(), 35.0 * kPi / 180.0, 1e-15);
  const glm::dvec3 a = falcon_angles_from_counts(glm::dvec3(0.0, 1000.0, -1000.0));
  EXPECT_NEAR(a.x, 35.0 * kPi / 180.0, 1e-12);
  EXPECT_NEAR(a.y - a.x, 1000.0 * falcon_rad_per_count(), 1e-12);
  const glm::dvec3 back = falcon_counts_from_angles(a);
  EXPECT_NEAR(back.y, 1000.0, 1e-9);
  EXPECT_NEAR(back.z, -1000.0, 1e-9);
}

TEST(FalconKinematics, TheCentreIsSymmetricAndTheAxisPointsAtTheUser) {
  const auto centre = falcon_joint_angles_rad(glm::dvec3(0.0));
  ASSERT_TRUE(centre);
  EXPECT_NEAR(centre->x, centre->y, 1e-12);
  EXPECT_NEAR(centre->x, centre->z, 1e-12);
  // Pulling the grip toward the user (+z) opens all three thighs alike.
  const auto out = falcon_joint_angles_rad(glm::dvec3(0.0, 0.0, 20.0));
  ASSERT_TRUE(out);
  EXPECT_GT(out->x, centre->x);
  EXPECT_NEAR(out->x, out->z, 1e-12);
  // Leg 1 is the top one (libnifalcon StamperUtils.h: legs from the top,
  // clockwise seen from the front): raising the grip folds its thigh and
  // opens the two lower ones.
  const auto up = falcon_joint_angles_rad(glm::dvec3(0.0, 10.0, 0.0));
  ASSERT_TRUE(up);
  EXPECT_LT(up->x, centre->x);
  EXPECT_GT(up->y, centre->y);
  EXPECT_GT(up->z, centre->z);
}

TEST(FalconKinematics, PositionToEncodersToPositionWithin0p01MmOverTheWorkspace) {
  double worst_mm = 0.0;
  int points = 0;
  for (const glm::dvec3& p : workspace_grid()) {
    const auto angles = falcon_joint_angles_rad(p);
    ASSERT_TRUE(angles) << p.x << " " << p.y << " " << p.z;
    const glm::dvec3 counts = falcon_counts_from_angles(*angles);
    const auto back = falcon_position_mm(falcon_angles_from_counts(counts));
    ASSERT_TRUE(back) << p.x << " " << p.y << " " << p.z;
    worst_mm = std::max(worst_mm, glm::length(*back - p));
    ++points;
  }
  EXPECT_GT(points, 2000);
  EXPECT_LT(worst_mm, 0.01);
}

TEST(FalconKinematics, WholeEncoderCountsRoundTripToTheSameCounts) {
  // The firmware's counts are integers: one count moves the grip about
  // 0.04 mm, so a position read back is within half a count's motion of the
  // one sent, and reading that position again gives the same counts.
  double worst_mm = 0.0;
  for (const glm::dvec3& p : workspace_grid(10.0)) {
    const glm::dvec3 counts = glm::round(falcon_counts_from_angles(*falcon_joint_angles_rad(p)));
    const auto back = falcon_position_mm(falcon_angles_from_counts(counts), p);
    ASSERT_TRUE(back);
    worst_mm = std::max(worst_mm, glm::length(*back - p));
    const glm::dvec3 again = falcon_counts_from_angles(*falcon_joint_angles_rad(*back));
    EXPECT_NEAR(glm::length(again - counts), 0.0, 1e-6);
  }
  EXPECT_LT(worst_mm, 0.1);
}

TEST(FalconKinematics, ForwardKinematicsFindsThePoseFromAFarGuess) {
  const glm::dvec3 p(25.0, -20.0, 15.0);
  const auto angles = falcon_joint_angles_rad(p);
  ASSERT_TRUE(angles);
  const auto back = falcon_position_mm(*angles, glm::dvec3(-30.0, 20.0, -20.0));
  ASSERT_TRUE(back);
  EXPECT_LT(glm::length(*back - p), 1e-4);
  // Angles no pose has.
  EXPECT_FALSE(falcon_position_mm(glm::dvec3(3.0, -3.0, 3.0)));
}

TEST(FalconKinematics, TheJacobianMatchesFiniteDifferencesOfTheInverse) {
  constexpr double h = 1e-4;  // mm
  double worst = 0.0;
  for (const glm::dvec3& p : workspace_grid(10.0)) {
    const auto j = falcon_angle_jacobian(p);
    ASSERT_TRUE(j);
    for (int c = 0; c < 3; ++c) {
      glm::dvec3 dp(0.0);
      dp[c] = h;
      const glm::dvec3 fd =
          (*falcon_joint_angles_rad(p + dp) - *falcon_joint_angles_rad(p - dp)) / (2 * h);
      for (int leg = 0; leg < 3; ++leg)
        worst = std::max(worst, std::abs((*j)[c][leg] - fd[leg]));
    }
  }
  // Entries are ~0.01 rad/mm.
  EXPECT_LT(worst, 1e-8);
}

TEST(FalconKinematics, TorquesDoTheSameWorkAsTheForce) {
  // Virtual work: for a small motion dp, tau . dangles = f . dp.
  for (const glm::dvec3& p :
       {glm::dvec3(0.0), glm::dvec3(20.0, -15.0, 10.0), glm::dvec3(-10.0, 25.0, -20.0)}) {
    const glm::dvec3 f(1.5, -4.0, 6.0);
    const auto tau = falcon_joint_torques_nm(p, f);
    ASSERT_TRUE(tau);
    const glm::dvec3 dp(0.01, 0.02, -0.015);  // mm; central differences
    const glm::dvec3 dangles = *falcon_joint_angles_rad(p + dp) - *falcon_joint_angles_rad(p - dp);
    EXPECT_NEAR(glm::dot(*tau, dangles), glm::dot(f, 2.0 * dp) * 1e-3, 1e-10);
  }
}

TEST(FalconKinematics, MotorCommandsAreTheScaledTorquesAndPushTheRightWay) {
  const glm::dvec3 p(5.0, -5.0, 10.0);
  const glm::dvec3 f(0.0, 0.0, 4.0);
  const auto tau = falcon_joint_torques_nm(p, f);
  ASSERT_TRUE(tau);
  const auto cmd = falcon_motor_commands(p, f, {});
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(cmd[static_cast<size_t>(i)], (*tau)[i] * falcon_command_per_nm(), 1.0) << i;
  // Opposite forces, opposite commands.
  const auto neg = falcon_motor_commands(p, -f, {});
  for (size_t i = 0; i < 3; ++i)
    EXPECT_NEAR(neg[i], -cmd[i], 1.0) << i;
}

TEST(FalconKinematics, ClampingKeepsTheDirection) {
  const glm::dvec3 p(-12.0, 8.0, -6.0);
  const glm::dvec3 dir = glm::normalize(glm::dvec3(3.0, -1.0, 2.0));
  FalconMotorLimits limits;  // 8 N
  // A 100 N force is sent as 8 N along the same line.
  const auto big = falcon_motor_commands(p, dir * 100.0, limits);
  const auto eight = falcon_motor_commands(p, dir * 8.0, limits);
  for (size_t i = 0; i < 3; ++i)
    EXPECT_EQ(big[i], eight[i]) << i;
  // A motor limit scales all three: the largest sits at the limit and the
  // ratios hold (to the rounding of a count).
  limits.max_command = 500;
  const auto capped = falcon_motor_commands(p, dir * 8.0, limits);
  int largest = 0;
  size_t which = 0;
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_LE(std::abs(capped[i]), 500) << i;
    if (std::abs(eight[i]) > largest) {
      largest = std::abs(eight[i]);
      which = i;
    }
  }
  ASSERT_GT(largest, 500);
  EXPECT_EQ(std::abs(capped[which]), 500);
  for (size_t i = 0; i < 3; ++i)
    EXPECT_NEAR(capped[i], eight[i] * 500.0 / largest, 1.0) << i;
}

TEST(FalconKinematics, CommandsNeverLeaveTheInt16RangeAndNonsenseGivesZero) {
  FalconMotorLimits limits;
  limits.max_force_n = 1e9f;  // only the motor limit holds
  for (const glm::dvec3& p : workspace_grid(20.0)) {
    const auto c = falcon_motor_commands(p, glm::dvec3(1e7, -3e7, 2e7), limits);
    int largest = 0;
    for (int16_t v : c) {
      EXPECT_GE(v, -32767);
      largest = std::max(largest, std::abs(int{v}));
    }
    EXPECT_EQ(largest, 32767);
  }
  const auto nan = falcon_motor_commands(glm::dvec3(0.0), glm::dvec3(std::nan(""), 1.0, 0.0), {});
  EXPECT_EQ(nan, (std::array<int16_t, 3>{0, 0, 0}));
  const auto inf = falcon_motor_commands(glm::dvec3(0.0), glm::dvec3(INFINITY, 0.0, 0.0), {});
  EXPECT_EQ(inf, (std::array<int16_t, 3>{0, 0, 0}));
  // Out of reach: no Jacobian, no force.
  const auto far =
      falcon_motor_commands(glm::dvec3(0.0, 0.0, 500.0), glm::dvec3(1.0, 0.0, 0.0), {});
  EXPECT_EQ(far, (std::array<int16_t, 3>{0, 0, 0}));
}

}  // namespace
}  // namespace sculpt::hal::falcon
