#pragma once
// The Falcon's delta mechanism: three legs, each a motor-driven thigh and a
// parallelogram shin, keeping the grip parallel to itself (Stamper's 3-DOF
// translational manipulator, R. E. Stamper, PhD thesis 97-4, University of
// Maryland 1997, as the Falcon's geometry is given in libnifalcon).
//
// Frames and units: positions in mm in the device frame of ForceDevice (x
// right, y up, z toward the user, origin at the workspace centre, 110 mm in
// front of the legs' hip plane); joint angles in radians (each thigh's angle,
// "theta1" in Stamper); encoder counts as the firmware reports them; forces in
// N; joint torques in N·m; motor commands in the firmware's units (int16).
//
// encoders -> angles is linear; angles -> position (forward kinematics) has
// no closed form and is solved by Newton's method on the closed-form inverse.

#include <array>
#include <cstdint>
#include <optional>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace sculpt::hal::falcon {

/// Radians of thigh per encoder count (0.0364 degrees).
double falcon_rad_per_count();
/// Thigh angle at encoder count 0, rad (35 degrees).
double falcon_angle_at_zero_count_rad();

/// Encoder counts (fractional allowed) -> thigh angles, rad.
glm::dvec3 falcon_angles_from_counts(glm::dvec3 counts);
/// Thigh angles, rad -> encoder counts, fractional (round for the firmware's).
glm::dvec3 falcon_counts_from_angles(glm::dvec3 angles_rad);

/// Inverse kinematics: the three thigh angles, rad, that put the grip at
/// position_mm; nullopt where the mechanism cannot reach.
std::optional<glm::dvec3> falcon_joint_angles_rad(glm::dvec3 position_mm);

/// d(angles)/d(position) at position_mm, rad/mm: row i (m[.][i] in glm's
/// column-major terms) is the gradient of leg i's angle. nullopt where the
/// inverse kinematics fails or the legs are singular.
std::optional<glm::dmat3> falcon_angle_jacobian(glm::dvec3 position_mm);

/// Forward kinematics: the grip position, mm, for thigh angles, rad, found by
/// Newton's method from `guess_mm` (the previous position; the centre by
/// default) to within 1e-6 mm; nullopt when it does not converge (angles no
/// pose has, or a guess across a singularity).
std::optional<glm::dvec3> falcon_position_mm(glm::dvec3 angles_rad,
                                             glm::dvec3 guess_mm = glm::dvec3(0.0));

/// The joint torques, N·m, that give force_n at the grip at position_mm:
/// the transposed Jacobian, tau = (dp/dangles)^T f. nullopt as for the Jacobian.
std::optional<glm::dvec3> falcon_joint_torques_nm(glm::dvec3 position_mm, glm::dvec3 force_n);

struct FalconMotorLimits {
  /// The largest force sent, N (the force limits table's figure).
  float max_force_n = 8.0f;
  /// The largest motor command, firmware units.
  int16_t max_command = 32767;
};

/// Motor commands for force_n at position_mm: the force is first clamped to
/// max_force_n and the commands then to max_command, each by scaling the
/// whole vector, so the force keeps its direction. Zero commands for a
/// non-finite force or a pose with no Jacobian.
std::array<int16_t, 3> falcon_motor_commands(glm::dvec3 position_mm, glm::dvec3 force_n,
                                             const FalconMotorLimits& limits);

/// Motor units per N·m of thigh torque (libnifalcon's empirical scale).
double falcon_command_per_nm();

}  // namespace sculpt::hal::falcon
