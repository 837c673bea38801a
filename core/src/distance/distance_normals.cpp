#include "sculpt/core/distance/distance_normals.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace sculpt::core {
namespace {

// Central difference at a voxel, one-sided at the faces.
glm::vec3 voxel_gradient(const DenseGrid<float>& d, glm::ivec3 v) {
  const glm::ivec3 dims = d.dims();
  glm::vec3 g(0.0f);
  for (int axis = 0; axis < 3; ++axis) {
    glm::ivec3 lo = v, hi = v;
    lo[axis] = std::max(0, v[axis] - 1);
    hi[axis] = std::min(dims[axis] - 1, v[axis] + 1);
    const int span = hi[axis] - lo[axis];
    if (span > 0) g[axis] = (d.at(hi.x, hi.y, hi.z) - d.at(lo.x, lo.y, lo.z)) / float(span);
  }
  return g;
}

// The trilinear blend at p of a value per voxel (value_at), p clamped onto
// the grid of d.
template <class T, class ValueAt>
T trilinear_blend(const DenseGrid<float>& d, glm::vec3 p, ValueAt value_at) {
  const glm::ivec3 dims = d.dims();
  if (dims.x == 0 || dims.y == 0 || dims.z == 0) return T(0.0f);
  const glm::vec3 q = glm::clamp(p, glm::vec3(0.0f), glm::vec3(dims - 1));
  const glm::ivec3 b = glm::min(glm::ivec3(glm::floor(q)), glm::max(dims - 2, glm::ivec3(0)));
  const glm::vec3 t = q - glm::vec3(b);
  T sum(0.0f);
  for (int c = 0; c < 8; ++c) {
    const glm::ivec3 o(c & 1, (c >> 1) & 1, c >> 2);
    const glm::ivec3 v = glm::min(b + o, dims - 1);
    const float w = (o.x ? t.x : 1 - t.x) * (o.y ? t.y : 1 - t.y) * (o.z ? t.z : 1 - t.z);
    sum += w * value_at(v);
  }
  return sum;
}

}  // namespace

float sample_trilinear(const DenseGrid<float>& d, glm::vec3 p) {
  return trilinear_blend<float>(d, p, [&](glm::ivec3 v) { return d.at(v.x, v.y, v.z); });
}

glm::vec3 distance_gradient(const DenseGrid<float>& d, glm::vec3 p) {
  return trilinear_blend<glm::vec3>(d, p, [&](glm::ivec3 v) { return voxel_gradient(d, v); });
}

glm::vec3 distance_normal(const DenseGrid<float>& d, glm::vec3 p) {
  const glm::vec3 g = distance_gradient(d, p);
  const float len = glm::length(g);
  return len > 0.0f ? g / len : glm::vec3(0.0f);
}

void set_normals_from_distance(const DenseGrid<float>& d, Mesh& mesh) {
  mesh.normals.resize(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    mesh.normals[i] = distance_normal(d, mesh.positions[i]);
}

}  // namespace sculpt::core
