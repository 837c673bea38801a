#pragma once
// Point-to-triangle distance in double precision, written independently of
// core/distance (projection onto the plane by the normal, else the nearest
// of the three edges): the reference the distance tests compare against.

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace sculpt::test {

inline double distance_in_double(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  auto segment = [&](glm::dvec3 s, glm::dvec3 e) {
    const double len2 = glm::dot(e - s, e - s);
    const double t = len2 > 0.0 ? std::clamp(glm::dot(p - s, e - s) / len2, 0.0, 1.0) : 0.0;
    return glm::length(p - (s + t * (e - s)));
  };
  double best = std::min({segment(a, b), segment(b, c), segment(c, a)});
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double n2 = glm::dot(n, n);
  if (n2 > 0.0) {
    const double u = glm::dot(p - a, glm::cross(c - a, n)) / n2;
    const double v = glm::dot(p - a, glm::cross(n, b - a)) / n2;
    if (u >= 0.0 && v >= 0.0 && u + v <= 1.0)
      best = std::min(best, std::abs(glm::dot(p - a, n)) / std::sqrt(n2));
  }
  return best;
}

}  // namespace sculpt::test
