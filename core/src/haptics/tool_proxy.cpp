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
  const size_t n = shell_.points.size();
  for (const glm::vec3& p : shell_.points) {
    px_.push_back(p.x);
    py_.push_back(p.y);
    pz_.push_back(p.z);
  }
  wx_.resize(n);
  wy_.resize(n);
  wz_.resize(n);
  nearest_.resize(n);
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

namespace {

// Where the shell points are and which stored value is nearest each: a flat
// loop over the points' coordinates (one array per axis) that vectorises.
inline __attribute__((always_inline)) void place_points_body(
    const float* px, const float* py, const float* pz, size_t n, const float* m, glm::vec3 t,
    glm::ivec3 origin, int edge, float* wx, float* wy, float* wz, int32_t* nearest) {
  const float hi = float(edge - 1);
  for (size_t i = 0; i < n; ++i) {
    const float x = m[0] * px[i] + m[3] * py[i] + m[6] * pz[i] + t.x;
    const float y = m[1] * px[i] + m[4] * py[i] + m[7] * pz[i] + t.y;
    const float z = m[2] * px[i] + m[5] * py[i] + m[8] * pz[i] + t.z;
    wx[i] = x;
    wy[i] = y;
    wz[i] = z;
    // Round to the nearest voxel, clamped into the patch.
    const float lx = std::min(std::max(x - float(origin.x) + 0.5f, 0.0f), hi);
    const float ly = std::min(std::max(y - float(origin.y) + 0.5f, 0.0f), hi);
    const float lz = std::min(std::max(z - float(origin.z) + 0.5f, 0.0f), hi);
    nearest[i] = (int32_t(lz) * edge + int32_t(ly)) * edge + int32_t(lx);
  }
}

// Dispatched by hand: an ifunc (target_clones) resolver runs before
// ThreadSanitizer's runtime is up and crashes the instrumented build.
__attribute__((target("avx2"))) void place_points_avx2(const float* px, const float* py,
                                                       const float* pz, size_t n, const float* m,
                                                       glm::vec3 t, glm::ivec3 origin, int edge,
                                                       float* wx, float* wy, float* wz,
                                                       int32_t* nearest) {
  place_points_body(px, py, pz, n, m, t, origin, edge, wx, wy, wz, nearest);
}

void place_points_baseline(const float* px, const float* py, const float* pz, size_t n,
                           const float* m, glm::vec3 t, glm::ivec3 origin, int edge, float* wx,
                           float* wy, float* wz, int32_t* nearest) {
  place_points_body(px, py, pz, n, m, t, origin, edge, wx, wy, wz, nearest);
}

void place_points(const float* px, const float* py, const float* pz, size_t n, const float* m,
                  glm::vec3 t, glm::ivec3 origin, int edge, float* wx, float* wy, float* wz,
                  int32_t* nearest) {
  static const bool avx2 = __builtin_cpu_supports("avx2");
  (avx2 ? place_points_avx2 : place_points_baseline)(px, py, pz, n, m, t, origin, edge, wx, wy, wz,
                                                     nearest);
}

}  // namespace

ToolProxy::Wrench ToolProxy::contact_wrench(const PatchSnapshot& field, glm::vec3 position,
                                            glm::quat orientation) {
  Wrench w;
  const glm::mat3 rotation = glm::mat3_cast(orientation);
  const size_t n = shell_.points.size();
  place_points(px_.data(), py_.data(), pz_.data(), n, &rotation[0][0], position, field.origin,
               field.edge, wx_.data(), wy_.data(), wz_.data(), nearest_.data());
  const float* phi = field.phi.data();
  for (size_t i = 0; i < n; ++i) {
    // Most points are well outside the material: the nearest stored value
    // (at most 0.87 voxel off) rules them out.
    const float near = phi[nearest_[i]];
    w.clearance = std::min(w.clearance, near - 0.9f);
    if (near > 0.9f) continue;
    const glm::vec3 p(wx_[i], wy_[i], wz_[i]);
    const FieldSample s = field.sample(p);
    if (s.phi_vox >= 0.0f) continue;
    const glm::vec3 arm = p - position;
    const float length = glm::length(s.gradient);
    const glm::vec3 normal = length > 1e-6f ? s.gradient / length : -rotation * shell_.normals[i];
    // Penalty force pushing the point out along the material's normal.
    const glm::vec3 f = k_n_per_vox_ * -s.phi_vox * normal;
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
    // A turn moves a point by at most reach * angle; the move gets the rest.
    const glm::vec3 turn = limited((twist + w.torque) / (kr_n_vox_per_rad_ + w.rotational),
                                   std::max(options_.max_turn_rad, 0.5f * clearance / reach));
    const glm::vec3 move =
        limited((pull + w.force) / (k_n_per_vox_ + w.stiffness),
                std::max(options_.max_step_vox, clearance - reach * glm::length(turn)));
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
