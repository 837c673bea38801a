// The Falcon's kinematics, written from the geometry (not from a port of any
// implementation):
//
// Geometry, libnifalcon include/falcon/core/FalconGeometry.h (after Stamper's
// thesis, figure on p. 30), here in mm: thigh a = 60, shin parallelogram
// side b = 102.5, effector offsets c = 14.43 and f = -25, the two short
// links of the parallelogram d = e = 11.25, hip offsets r = 40 and s =
// -23.09; the legs stand at phi = 90, -30 and -150 degrees, each turned a
// further 15 degrees. Encoders, FalconKinematic.h getTheta(): a 320-slot
// wheel read in quadrature (1280 counts per motor turn) on a 14.25 mm
// capstan driving a 110 mm thigh sector, 35 degrees at count 0.
//
// Each leg in its own frame (u, v, w) = rotation of (x, y, z) by phi about z,
// less the hip offset (r, s, 0). With the thigh at angle t the knee is at
// a (cos t, 0, sin t); the vector from knee to grip, corrected by the
// effector offsets, D = (P_u + c - a cos t, P_v + f, P_w - a sin t), is the
// two short links (d + e, in the u-w plane, radially) plus the shin (length
// b), so one scalar constraint ties the leg's angle to the grip:
//   F(P, t) = (sqrt(D_u^2 + D_w^2) - (d + e))^2 + D_v^2 - b^2 = 0.
// Inverse kinematics solves it for t in closed form (a circle meets a
// circle); the Jacobian comes from implicit differentiation,
// dt/dp = -(dF/dp) / (dF/dt); the forward kinematics is Newton's method on
// the inverse. Of the two circle intersections the knee-out one is the
// Falcon's (it matches libnifalcon's choice of root in
// src/kinematic/FalconKinematicStamper.cpp, checked numerically).
//
// The workspace centre, 110 mm in front of the hip plane on the axis, is the
// one libnifalcon's examples/falcon_test_cli/FalconSphereTest.cpp subtracts.
// The motor scale and sign, -10000 units per N·m, are libnifalcon's
// FalconKinematicStamper::getForces(); its analytic Jacobian's z column
// differs from the derivative of its own inverse kinematics (about 25 % at
// the centre), which ours is tested against.

#include "falcon_kinematics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace sculpt::hal::falcon {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kThighMm = 60.0;       // a
constexpr double kShinMm = 102.5;       // b
constexpr double kEffectorUMm = 14.43;  // c
constexpr double kShortLinksMm = 22.5;  // d + e
constexpr double kEffectorVMm = -25.0;  // f
constexpr double kHipUMm = 40.0;        // r
constexpr double kHipVMm = -23.09;      // s
constexpr double kCentreZMm = 110.0;
constexpr double kLegTurnRad = kPi / 12.0;
constexpr double kLegRad[3] = {kPi / 2 + kLegTurnRad, -kPi / 6 + kLegTurnRad,
                               -5 * kPi / 6 + kLegTurnRad};

constexpr double kCapstanMm = 14.25;
constexpr double kThighSectorMm = 110.0;
constexpr double kCountsPerMotorTurn = 320.0 * 4.0;
constexpr double kZeroCountDeg = 35.0;
constexpr double kCommandPerNm = -10000.0;

// The grip in leg i's frame.
glm::dvec3 in_leg_frame(glm::dvec3 position_mm, int leg) {
  const glm::dvec3 p{position_mm.x, position_mm.y, position_mm.z + kCentreZMm};
  const double cs = std::cos(kLegRad[leg]);
  const double sn = std::sin(kLegRad[leg]);
  return {cs * p.x + sn * p.y - kHipUMm, -sn * p.x + cs * p.y - kHipVMm, p.z};
}

std::optional<double> leg_angle(const glm::dvec3& P) {
  const double dv = P.y + kEffectorVMm;
  if (std::abs(dv) > kShinMm) return std::nullopt;
  // The shin's reach in the u-w plane plus the short links: the radius of
  // the circle, centred on the effector point, that the knee must lie on.
  const double reach = kShortLinksMm + std::sqrt(kShinMm * kShinMm - dv * dv);
  const double A = P.x + kEffectorUMm;
  const double B = P.z;
  const double dist = std::hypot(A, B);
  if (dist < 1e-9) return std::nullopt;
  const double cos_arg =
      (A * A + B * B + kThighMm * kThighMm - reach * reach) / (2 * kThighMm * dist);
  if (std::abs(cos_arg) > 1.0) return std::nullopt;
  return std::atan2(B, A) - std::acos(cos_arg);
}

}  // namespace

double falcon_rad_per_count() {
  return 2 * kPi * (kCapstanMm / kThighSectorMm) / kCountsPerMotorTurn;
}

double falcon_angle_at_zero_count_rad() {
  return kZeroCountDeg * kPi / 180.0;
}

double falcon_command_per_nm() {
  return kCommandPerNm;
}

glm::dvec3 falcon_angles_from_counts(glm::dvec3 counts) {
  return counts * falcon_rad_per_count() + glm::dvec3(falcon_angle_at_zero_count_rad());
}

glm::dvec3 falcon_counts_from_angles(glm::dvec3 angles_rad) {
  return (angles_rad - glm::dvec3(falcon_angle_at_zero_count_rad())) / falcon_rad_per_count();
}

std::optional<glm::dvec3> falcon_joint_angles_rad(glm::dvec3 position_mm) {
  glm::dvec3 out;
  for (int i = 0; i < 3; ++i) {
    const auto t = leg_angle(in_leg_frame(position_mm, i));
    if (!t) return std::nullopt;
    out[i] = *t;
  }
  return out;
}

std::optional<glm::dmat3> falcon_angle_jacobian(glm::dvec3 position_mm) {
  glm::dmat3 j(0.0);
  for (int i = 0; i < 3; ++i) {
    const glm::dvec3 P = in_leg_frame(position_mm, i);
    const auto t = leg_angle(P);
    if (!t) return std::nullopt;
    const double du = P.x + kEffectorUMm - kThighMm * std::cos(*t);
    const double dv = P.y + kEffectorVMm;
    const double dw = P.z - kThighMm * std::sin(*t);
    const double rho = std::hypot(du, dw);
    if (rho < 1e-9) return std::nullopt;
    const double k = 2 * (rho - kShortLinksMm) / rho;
    // dF/dP in the leg frame, then back to the device frame (the transpose
    // of the rotation; the hip offset does not vary).
    const glm::dvec3 grad_leg{k * du, 2 * dv, k * dw};
    const double cs = std::cos(kLegRad[i]);
    const double sn = std::sin(kLegRad[i]);
    const glm::dvec3 grad{cs * grad_leg.x - sn * grad_leg.y, sn * grad_leg.x + cs * grad_leg.y,
                          grad_leg.z};
    const double dF_dt = k * kThighMm * (du * std::sin(*t) - dw * std::cos(*t));
    if (std::abs(dF_dt) < 1e-12) return std::nullopt;
    for (int c = 0; c < 3; ++c)
      j[c][i] = -grad[c] / dF_dt;
  }
  if (std::abs(glm::determinant(j)) < 1e-15) return std::nullopt;
  return j;
}

std::optional<glm::dvec3> falcon_position_mm(glm::dvec3 angles_rad, glm::dvec3 guess_mm) {
  // Newton on angles(p) = target, stepping with the inverse of the angle
  // Jacobian; a step landing where the legs cannot reach is halved. From
  // anywhere in the workspace it converges in 3-5 steps.
  constexpr int kMaxSteps = 40;
  constexpr double kTolMm = 1e-6;
  glm::dvec3 p = guess_mm;
  auto angles = falcon_joint_angles_rad(p);
  if (!angles) {
    p = glm::dvec3(0.0);
    angles = falcon_joint_angles_rad(p);
  }
  for (int step = 0; step < kMaxSteps && angles; ++step) {
    const auto j = falcon_angle_jacobian(p);
    if (!j) return std::nullopt;
    glm::dvec3 delta = glm::inverse(*j) * (angles_rad - *angles);
    if (!std::isfinite(delta.x + delta.y + delta.z)) return std::nullopt;
    std::optional<glm::dvec3> next_angles;
    for (int halving = 0; halving < 20; ++halving) {
      next_angles = falcon_joint_angles_rad(p + delta);
      if (next_angles) break;
      delta *= 0.5;
    }
    if (!next_angles) return std::nullopt;
    p += delta;
    angles = next_angles;
    if (glm::length(delta) < kTolMm) return p;
  }
  return std::nullopt;
}

std::optional<glm::dvec3> falcon_joint_torques_nm(glm::dvec3 position_mm, glm::dvec3 force_n) {
  const auto j = falcon_angle_jacobian(position_mm);
  if (!j) return std::nullopt;
  // Virtual work: tau . d(angles) = f . dp, so tau = (dp/dangles)^T f; the
  // Jacobian is in mm/rad, hence N·mm, / 1000 for N·m.
  const glm::dmat3 dp_dangles = glm::inverse(*j);
  return glm::transpose(dp_dangles) * force_n * 1e-3;
}

std::array<int16_t, 3> falcon_motor_commands(glm::dvec3 position_mm, glm::dvec3 force_n,
                                             const FalconMotorLimits& limits) {
  std::array<int16_t, 3> out{0, 0, 0};
  const double magnitude = glm::length(force_n);
  if (!std::isfinite(magnitude)) return out;
  const double max_force = std::max(0.0, static_cast<double>(limits.max_force_n));
  if (magnitude > max_force) force_n *= max_force / magnitude;
  const auto tau = falcon_joint_torques_nm(position_mm, force_n);
  if (!tau) return out;
  glm::dvec3 command = *tau * kCommandPerNm;
  const double largest = std::max({std::abs(command.x), std::abs(command.y), std::abs(command.z)});
  const double max_command = std::clamp(static_cast<double>(limits.max_command), 0.0, 32767.0);
  // Scaling all three (not clipping each) keeps the torques' ratio and so
  // the force's direction when a motor saturates.
  if (largest > max_command) command *= max_command / largest;
  for (int i = 0; i < 3; ++i) {
    const double c = std::clamp(std::round(command[i]), -max_command, max_command);
    out[static_cast<size_t>(i)] = static_cast<int16_t>(c);
  }
  return out;
}

}  // namespace sculpt::hal::falcon
