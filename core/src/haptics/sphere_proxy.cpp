#include "sculpt/core/haptics/sphere_proxy.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace sculpt::core {
namespace {

// Below this clearance (in skins) the proxy counts as touching.
constexpr float kTouchingSkins = 2.0f;
// Motion shorter than this (voxels) is no motion.
constexpr float kStill = 1e-5f;
// Two normals closer than this (cosine, 30 degrees) are one constraint.
constexpr float kSameConstraint = 0.866f;

// How far p can go along dir before leaving the region where the patch is
// sampled exactly (first to last voxel centre).
float distance_to_patch_edge(const PatchSnapshot& field, glm::vec3 p, glm::vec3 dir) {
  const glm::vec3 local = p - glm::vec3(field.origin);
  const float hi = float(field.edge - 1);
  float t = std::numeric_limits<float>::max();
  for (int a = 0; a < 3; ++a) {
    if (dir[a] > 1e-7f) t = std::min(t, (hi - local[a]) / dir[a]);
    if (dir[a] < -1e-7f) t = std::min(t, local[a] / -dir[a]);
  }
  return std::max(t, 0.0f);
}

// m with the parts that push into the active constraints removed (Zilles &
// Salisbury: one plane, the edge line of two, nothing at a corner of three).
glm::vec3 constrained_motion(glm::vec3 m, const std::array<glm::vec3, 3>& normals, int count) {
  // Rounding leaves a projected motion a hair into its own plane: the
  // tolerance scales with the motion.
  const float tolerance = -1e-4f * glm::length(m);
  const auto violates = [&](glm::vec3 v) {
    for (int i = 0; i < count; ++i)
      if (glm::dot(v, normals[size_t(i)]) < tolerance) return true;
    return false;
  };
  if (!violates(m)) return m;
  for (int i = 0; i < count; ++i) {
    const glm::vec3 n = normals[size_t(i)];
    const glm::vec3 on_plane = m - glm::dot(m, n) * n;
    if (glm::dot(m, n) < 0.0f && !violates(on_plane)) return on_plane;
  }
  for (int i = 0; i < count; ++i)
    for (int j = i + 1; j < count; ++j) {
      const glm::vec3 edge = glm::cross(normals[size_t(i)], normals[size_t(j)]);
      const float length = glm::length(edge);
      if (length < 1e-4f) continue;
      const glm::vec3 e = edge / length;
      const glm::vec3 along = glm::dot(m, e) * e;
      if (!violates(along)) return along;
    }
  return glm::vec3(0.0f);
}

}  // namespace

SphereProxy::SphereProxy(const SphereProxyOptions& options) : options_(options) {}

float SphereProxy::clearance(const PatchSnapshot& field, glm::vec3 p, glm::vec3* normal) const {
  const FieldSample s = field.sample(p);
  if (normal) {
    const float length = glm::length(s.gradient);
    *normal = length > 1e-6f ? s.gradient / length : glm::vec3(0.0f, 0.0f, 1.0f);
  }
  return s.phi_vox - options_.radius_vox;
}

glm::vec3 SphereProxy::onto_surface(const PatchSnapshot& field, glm::vec3 p) const {
  for (int i = 0; i < 4; ++i) {
    const FieldSample s = field.sample(p);
    const float error = s.phi_vox - options_.radius_vox - options_.skin_vox;
    const float g2 = glm::dot(s.gradient, s.gradient);
    if (std::abs(error) < 1e-4f || g2 < 1e-12f) break;
    p -= error * s.gradient / g2;
  }
  return p;
}

glm::vec3 SphereProxy::trace(const PatchSnapshot& field, glm::vec3 from, glm::vec3 to,
                             bool* blocked) const {
  *blocked = false;
  glm::vec3 p = from;
  const float skin = options_.skin_vox;
  for (int i = 0; i < 256; ++i) {
    const glm::vec3 d = to - p;
    const float remaining = glm::length(d);
    if (remaining < kStill) return to;
    const glm::vec3 dir = d / remaining;
    glm::vec3 n;
    const float g = clearance(field, p, &n);
    float step = g - skin;
    if (g <= kTouchingSkins * skin) {
      // Touching: only a motion away from the surface may go on, by a short
      // step checked afterwards (phi - r alone would allow none).
      if (glm::dot(dir, n) <= 0.0f) {
        *blocked = true;
        return p;
      }
      step = std::max(step, 0.1f * glm::dot(dir, n));
    }
    const float edge = distance_to_patch_edge(field, p, dir);
    step = std::min({step, remaining, edge});
    if (step < kStill) return p;  // at the patch's edge: wait for it to follow
    glm::vec3 next = p + dir * step;
    if (clearance(field, next, nullptr) < skin) {
      // The field is steeper than 1 here (a sampled distance is only nearly
      // one): close in on phi - r = skin by bisection, so the proxy rests on
      // the skin and not somewhere above it.
      for (int k = 0; k < 16; ++k) {
        const glm::vec3 mid = 0.5f * (p + next);
        (clearance(field, mid, nullptr) < skin ? next : p) = mid;
      }
      *blocked = true;
      return p;
    }
    p = next;
  }
  return p;
}

void SphereProxy::reset(const PatchSnapshot& field, glm::vec3 position_vox) {
  glm::vec3 p = position_vox;
  for (int i = 0; i < 64; ++i) {
    glm::vec3 n;
    const float g = clearance(field, p, &n);
    if (g >= options_.skin_vox) break;
    p += (options_.skin_vox - g + 0.01f) * n;
  }
  state_ = ProxyState{};
  state_.position_vox = p;
  placed_ = true;
}

const ProxyState& SphereProxy::update(const PatchSnapshot& field, glm::vec3 device_vox) {
  // The patch must know the distance out to r and beyond (band_for_sphere).
  assert(field.clamp_vox > options_.radius_vox + kTouchingSkins * options_.skin_vox);
  if (!placed_) reset(field, device_vox);
  const float skin = options_.skin_vox;
  // Material added under the proxy (a dab, an undo) lifts it out first.
  if (clearance(field, state_.position_vox, nullptr) < skin) {
    const bool sliding = state_.sliding;
    reset(field, state_.position_vox);
    state_.sliding = sliding;
  }
  glm::vec3 x = state_.position_vox;
  std::array<glm::vec3, 3> normals{};
  int active = 0;
  bool touched = false;
  glm::vec3 held = x, held_normal(0.0f);
  state_.at_patch_edge = false;

  // Once touching, the proxy heads for the device's projection onto the
  // tangent plane where the contact began this update (Zilles & Salisbury's
  // goal), not for the device itself: a device pushed straight in then holds
  // the proxy where it entered, however deep it goes, instead of letting it
  // run round the far side of the shape.
  glm::vec3 goal = device_vox;
  for (int step = 0; step < options_.max_steps; ++step) {
    const glm::vec3 m = goal - x;
    if (glm::length(m) < kStill) break;
    glm::vec3 n;
    const float g = clearance(field, x, &n);
    const bool touching = g <= kTouchingSkins * skin;
    if (!touching || (active == 0 && glm::dot(m, n) >= 0.0f)) {
      bool blocked = false;
      const glm::vec3 reached = trace(field, x, goal, &blocked);
      if (!blocked && glm::length(goal - reached) > kStill) state_.at_patch_edge = true;
      const bool moved = glm::length(reached - x) > kStill;
      x = reached;
      if (!blocked) break;
      if (!moved && active > 0) break;
      continue;
    }
    if (!touched) {
      touched = true;
      held = x;
      held_normal = n;
      goal = device_vox - glm::dot(device_vox - x, n) * n;
    }
    // A normal within kSameConstraint of one already met this update is that
    // constraint, moved along a curved surface: it replaces it. A normal
    // farther from all of them is a new face (an edge or corner was met).
    int same = -1;
    float best = kSameConstraint;
    for (int i = 0; i < active; ++i) {
      const float c = glm::dot(normals[size_t(i)], n);
      if (c > best) best = c, same = i;
    }
    if (same >= 0) {
      normals[size_t(same)] = n;
    } else {
      if (active == 3) normals[0] = normals[1], normals[1] = normals[2], active = 2;
      normals[size_t(active++)] = n;
    }
    const glm::vec3 slide = constrained_motion(goal - x, normals, active);
    const float length = glm::length(slide);
    if (length < kStill) break;
    const glm::vec3 next =
        onto_surface(field, x + slide * (std::min(length, options_.slide_step_vox) / length));
    if (glm::length(next - x) < kStill) break;
    x = next;
  }

  // Friction holds the proxy back from where the frictionless slide went.
  if (touched && options_.friction.enabled()) {
    const glm::vec3 before = x;
    x = apply_coulomb_friction(options_.friction, held, x, device_vox, held_normal, state_.sliding);
    if (x != before && x != held) x = onto_surface(field, x);
  } else {
    state_.sliding = touched;
  }

  glm::vec3 n;
  const float g = clearance(field, x, &n);
  state_.position_vox = x;
  state_.normal = n;
  state_.contact = g <= kTouchingSkins * skin + 1e-3f && glm::dot(device_vox - x, n) < 0.0f;
  state_.active_constraints = state_.contact ? std::max(active, 1) : 0;
  return state_;
}

}  // namespace sculpt::core
