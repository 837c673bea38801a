#include "sculpt/core/haptics/patch_snapshot.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include <glm/common.hpp>

namespace sculpt::core {

float PatchSnapshot::at(glm::ivec3 v) const {
  const glm::ivec3 l = v - origin;
  assert(l.x >= 0 && l.y >= 0 && l.z >= 0 && l.x < edge && l.y < edge && l.z < edge);
  return phi[(size_t(l.z) * edge + l.y) * edge + l.x];
}

FieldSample PatchSnapshot::sample(glm::vec3 p) const {
  assert(!empty());
  // The cell's lower corner stays at most edge - 2 so its upper corner exists.
  const float hi = float(edge - 1);
  const glm::vec3 local = glm::clamp(p - glm::vec3(origin), glm::vec3(0.0f), glm::vec3(hi));
  const glm::ivec3 c = glm::min(glm::ivec3(glm::floor(local)), glm::ivec3(edge - 2));
  const glm::vec3 f = local - glm::vec3(c);
  const size_t sx = 1, sy = size_t(edge), sz = size_t(edge) * size_t(edge);
  const float* v = phi.data() + size_t(c.z) * sz + size_t(c.y) * sy + size_t(c.x);
  const float v000 = v[0], v100 = v[sx], v010 = v[sy], v110 = v[sy + sx];
  const float v001 = v[sz], v101 = v[sz + sx], v011 = v[sz + sy], v111 = v[sz + sy + sx];
  // Interpolate along x, then y, then z; the gradient is the exact derivative
  // of the same trilinear polynomial.
  const float x00 = v000 + f.x * (v100 - v000), x10 = v010 + f.x * (v110 - v010);
  const float x01 = v001 + f.x * (v101 - v001), x11 = v011 + f.x * (v111 - v011);
  const float y0 = x00 + f.y * (x10 - x00), y1 = x01 + f.y * (x11 - x01);
  FieldSample s;
  s.phi_vox = y0 + f.z * (y1 - y0);
  // The gradient is the trilinear blend of the central differences at the
  // eight corners: the plain derivative of the trilinear polynomial jumps from
  // cell to cell, and its direction (the contact normal) with it, by a few
  // degrees on a curved surface; the blend turns smoothly.
  const glm::ivec3 hi_index(edge - 1);
  const auto value = [&](glm::ivec3 q) {
    q = glm::clamp(q, glm::ivec3(0), hi_index);
    return phi[size_t(q.z) * sz + size_t(q.y) * sy + size_t(q.x)];
  };
  const auto corner_gradient = [&](glm::ivec3 q) {
    return glm::vec3(value(q + glm::ivec3(1, 0, 0)) - value(q - glm::ivec3(1, 0, 0)),
                     value(q + glm::ivec3(0, 1, 0)) - value(q - glm::ivec3(0, 1, 0)),
                     value(q + glm::ivec3(0, 0, 1)) - value(q - glm::ivec3(0, 0, 1))) *
           0.5f;
  };
  glm::vec3 g(0.0f);
  for (int k = 0; k < 8; ++k) {
    const glm::ivec3 o{k & 1, (k >> 1) & 1, k >> 2};
    const float w = (o.x ? f.x : 1.0f - f.x) * (o.y ? f.y : 1.0f - f.y) * (o.z ? f.z : 1.0f - f.z);
    g += w * corner_gradient(c + o);
  }
  s.gradient = g;
  return s;
}

}  // namespace sculpt::core
