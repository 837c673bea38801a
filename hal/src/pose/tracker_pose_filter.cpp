#include "sculpt/hal/pose/tracker_pose_filter.h"

#include <cmath>

namespace sculpt::hal {
namespace {

// Smoothing factor of an exponential filter with cutoff fc at step dt.
double alpha(double cutoff_hz, double dt_s) {
  const double tau = 1.0 / (2.0 * 3.14159265358979 * cutoff_hz);
  return 1.0 / (1.0 + tau / dt_s);
}

glm::dquat quat_of(const TrackerPose& p) {
  return glm::normalize(glm::dquat(p.quat_wxyz[0], p.quat_wxyz[1], p.quat_wxyz[2], p.quat_wxyz[3]));
}

}  // namespace

TrackerPose TrackerPoseFilter::restart(const TrackerPose& pose, int64_t t_ns) {
  initialised_ = true;
  t_prev_ns_ = t_ns;
  position_mm_ = glm::dvec3(pose.position_mm[0], pose.position_mm[1], pose.position_mm[2]);
  orientation_ = quat_of(pose);
  speed_mm_s_ = 0.0;
  turn_rad_s_ = 0.0;
  prev_ = pose;
  return pose;
}

TrackerPose TrackerPoseFilter::filter(const TrackerPose& pose, int64_t t_ns) {
  const glm::dvec3 p(pose.position_mm[0], pose.position_mm[1], pose.position_mm[2]);
  glm::dquat q = quat_of(pose);
  if (!params_.enabled) return pose;
  if (!initialised_) return restart(pose, t_ns);
  if (t_ns <= t_prev_ns_) return prev_;
  const double dt = static_cast<double>(t_ns - t_prev_ns_) * 1e-9;
  t_prev_ns_ = t_ns;
  // q and -q are one rotation: take the one nearer, or slerp goes the long way.
  if (glm::dot(q, orientation_) < 0.0) q = -q;
  const double a_d = alpha(params_.d_cutoff_hz, dt);
  // One speed for the whole position (not per axis): a diagonal motion is
  // as fast as one along an axis, so it is lagged the same.
  speed_mm_s_ = a_d * (glm::length(p - position_mm_) / dt) + (1.0 - a_d) * speed_mm_s_;
  // The angle of the step's rotation by atan2, precise for the small turns
  // between samples where acos of the dot product is not.
  const glm::dquat step = q * glm::conjugate(orientation_);
  const double turn =
      2.0 * std::atan2(glm::length(glm::dvec3(step.x, step.y, step.z)), std::fabs(step.w));
  turn_rad_s_ = a_d * (turn / dt) + (1.0 - a_d) * turn_rad_s_;
  const double a_p = alpha(params_.min_cutoff_hz + params_.beta_per_mm_s * speed_mm_s_, dt);
  const double a_q = alpha(params_.min_cutoff_hz + params_.beta_per_rad_s * turn_rad_s_, dt);
  position_mm_ += a_p * (p - position_mm_);
  orientation_ = glm::normalize(glm::slerp(orientation_, q, a_q));
  // Any finite pose is accepted, but a jump of 1e300 mm overflows the
  // speed; restarting from this sample keeps the filter from holding NaN.
  const bool finite = std::isfinite(speed_mm_s_) && std::isfinite(turn_rad_s_) &&
                      std::isfinite(position_mm_.x) && std::isfinite(position_mm_.y) &&
                      std::isfinite(position_mm_.z) && std::isfinite(orientation_.w);
  if (!finite) return restart(pose, t_ns);
  TrackerPose out = pose;
  out.position_mm = {position_mm_.x, position_mm_.y, position_mm_.z};
  out.quat_wxyz = {orientation_.w, orientation_.x, orientation_.y, orientation_.z};
  prev_ = out;
  return out;
}

}  // namespace sculpt::hal
