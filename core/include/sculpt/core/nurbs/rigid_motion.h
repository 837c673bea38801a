#pragma once
// A rigid motion p -> pivot + rotation * (p - pivot) + translation: what one
// step of the path constraint applies to the control points it moves
// (La Greca et al. §4.3: rotation by alpha_k about an axis through C(k/N),
// then translation by e_k).

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace sculpt::core::nurbs {

struct RigidMotion {
  glm::dmat3 rotation{1.0};  ///< orthonormal, determinant 1
  glm::dvec3 pivot{0.0};
  glm::dvec3 translation{0.0};

  glm::dvec3 apply(glm::dvec3 p) const { return pivot + rotation * (p - pivot) + translation; }
};

}  // namespace sculpt::core::nurbs
