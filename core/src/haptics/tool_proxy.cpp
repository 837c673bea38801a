#include "sculpt/core/haptics/tool_proxy.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace sculpt::core {
namespace {

// The rotation vector (axis times angle, radians) of unit quaternion q.
glm::vec3 rotation_vector(glm::quat q) {
  if (q.w < 0.0f) q = -q;  // the short way round
  const glm::vec3 axis(q.x, q.y, q.z);
  const float s = glm::length(axis);
  if (s < 1e-8f) return 2.0f * axis;
  return axis * (2.0f * std::atan2(s, q.w) / s);
}

glm::quat from_rotation_vector(glm::vec3 v) {
  const float angle = glm::length(v);
  if (angle < 1e-9f) return glm::normalize(glm::quat(1.0f, 0.5f * v.x, 0.5f * v.y, 0.5f * v.z));
  return glm::angleAxis(angle, v / angle);
}

glm::vec3 limited(glm::vec3 v, float max_length) {
  const float length = glm::length(v);
  return length > max_length ? v * (max_length / length) : v;
}

}  // namespace

ToolProxy::ToolProxy(PointShell shell, const ToolProxyOptions& options)
    : shell_(std::move(shell)), options_(options) {
  k_n_per_vox_ = options.stiffness_n_per_mm * options.voxel_mm;
  const float reach = std::max(shell_.reach_vox, 1.0f);
  kr_n_vox_per_rad_ = options.rotational_stiffness_nmm_per_rad > 0.0f
                          ? options.rotational_stiffness_nmm_per_rad / options.voxel_mm
                          : k_n_per_vox_ * reach * reach;
}

void ToolProxy::reset(glm::vec3 position_vox, glm::quat orientation) {
  state_ = ToolTick{};
  state_.position_vox = position_vox;
  state_.orientation = glm::normalize(orientation);
  placed_ = true;
}

ToolProxy::Wrench ToolProxy::contact_wrench(const PatchSnapshot& field, glm::vec3 position,
                                            glm::quat orientation) const {
  Wrench w;
  const glm::mat3 rotation = glm::mat3_cast(orientation);
  const float* phi = field.phi.data();
  const int edge = field.edge;
  for (size_t i = 0; i < shell_.points.size(); ++i) {
    const glm::vec3 arm = rotation * shell_.points[i];
    const glm::vec3 p = position + arm;
    // Most points are well outside the material: one stored value (the
    // nearest voxel's, at most 0.87 voxel off) rules them out.
    const glm::ivec3 l =
        glm::clamp(glm::ivec3(glm::round(p)) - field.origin, glm::ivec3(0), glm::ivec3(edge - 1));
    const float nearest =
        phi[(size_t(l.z) * size_t(edge) + size_t(l.y)) * size_t(edge) + size_t(l.x)];
    w.clearance = std::min(w.clearance, nearest - 0.9f);
    if (nearest > 0.9f) continue;
    const FieldSample s = field.sample(p);
    if (s.phi_vox >= 0.0f) continue;
    const float length = glm::length(s.gradient);
    const glm::vec3 n = length > 1e-6f ? s.gradient / length : -rotation * shell_.normals[i];
    // Penalty force pushing the point out along the material's normal.
    const glm::vec3 f = k_n_per_vox_ * -s.phi_vox * n;
    w.force += f;
    w.torque += glm::cross(arm, f);
    w.stiffness += k_n_per_vox_;
    w.rotational += k_n_per_vox_ * glm::dot(arm, arm);
    ++w.points;
  }
  return w;
}

const ToolTick& ToolProxy::update(const PatchSnapshot& field, glm::vec3 device_vox,
                                  glm::quat device) {
  device = glm::normalize(device);
  if (!placed_) reset(device_vox, device);
  glm::vec3 x = state_.position_vox;
  glm::quat q = state_.orientation;
  Wrench w;
  for (int step = 0; step < options_.steps; ++step) {
    w = contact_wrench(field, x, q);
    // Quasi-static: the move that would balance coupling and contact if
    // both were linear springs, bounded so the shell cannot jump a wall.
    const glm::vec3 pull = k_n_per_vox_ * (device_vox - x);
    const glm::vec3 twist = kr_n_vox_per_rad_ * rotation_vector(device * glm::inverse(q));
    // Away from the material the bound is the shell's clearance instead (no
    // point can reach the surface in a shorter move), so a free tool keeps
    // up with the hand.
    const float clearance = std::max(w.clearance, 0.0f);
    const float reach = std::max(shell_.reach_vox, 1.0f);
    const glm::vec3 move = limited((pull + w.force) / (k_n_per_vox_ + w.stiffness),
                                   std::max(options_.max_step_vox, 0.5f * clearance));
    const glm::vec3 turn = limited((twist + w.torque) / (kr_n_vox_per_rad_ + w.rotational),
                                   std::max(options_.max_turn_rad, 0.5f * clearance / reach));
    x += move;
    q = glm::normalize(from_rotation_vector(turn) * q);
  }
  w = contact_wrench(field, x, q);
  state_.position_vox = x;
  state_.orientation = q;
  state_.points_in_contact = w.points;
  state_.contact = w.points > 0;
  // Out of contact the proxy is only catching up with the hand: no force.
  state_.force_n = glm::vec3(0.0f);
  state_.torque_nm = glm::vec3(0.0f);
  if (state_.contact) {
    state_.force_n = limited(k_n_per_vox_ * (x - device_vox), options_.max_force_n);
    // N·voxel/rad * rad -> N·mm -> N·m.
    state_.torque_nm = limited(
        kr_n_vox_per_rad_ * rotation_vector(q * glm::inverse(device)) * options_.voxel_mm * 1e-3f,
        options_.max_torque_nm);
  }
  return state_;
}

}  // namespace sculpt::core
