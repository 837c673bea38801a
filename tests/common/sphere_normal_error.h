#pragma once
// How far a mesh's vertex normals are from a sphere's own normals at the
// vertices: the angle, in degrees, on average and at worst.

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "sculpt/core/mesh/mesh.h"

namespace sculpt::test {

struct NormalError {
  double mean_deg = 0.0, max_deg = 0.0;
};

/// The normals of `mesh` against those of a sphere around `centre`.
inline NormalError sphere_normal_error(const core::Mesh& mesh, glm::vec3 centre) {
  NormalError e;
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::dvec3 radial = glm::normalize(glm::dvec3(mesh.positions[i] - centre));
    const glm::dvec3 normal = glm::normalize(glm::dvec3(mesh.normals[i]));
    const double deg =
        std::acos(std::clamp(glm::dot(radial, normal), -1.0, 1.0)) * 180.0 / std::numbers::pi;
    e.mean_deg += deg;
    e.max_deg = std::max(e.max_deg, deg);
  }
  if (!mesh.positions.empty()) e.mean_deg /= static_cast<double>(mesh.positions.size());
  return e;
}

}  // namespace sculpt::test
