// Zones in parameter space. The paper asks for star-shaped hulls (after the
// SCODEF extensions of Raffin) precisely so that "the distance between a
// point in the hull and the constraint point can always be computed": the
// ray from (u, v) leaves the zone exactly once, which defines rho.

#include "sculpt/core/nurbs/parameter_zone.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>

namespace sculpt::core::nurbs {
namespace {

double cross(glm::dvec2 a, glm::dvec2 b) {
  return a.x * b.y - a.y * b.x;
}
bool finite(glm::dvec2 p) {
  return std::isfinite(p.x) && std::isfinite(p.y);
}

// Distance along the unit ray from `o` in direction `d` to the zone's border.
double exit_distance(const ParameterZone& z, glm::dvec2 o, glm::dvec2 d) {
  if (z.shape == ParameterZone::Shape::kCircle) {
    // |o + t d - c|^2 = r^2 with |d| = 1, o inside: the positive root.
    const glm::dvec2 oc = o - z.centre;
    const double b = oc.x * d.x + oc.y * d.y;
    const double c = oc.x * oc.x + oc.y * oc.y - z.radius * z.radius;
    return -b + std::sqrt(std::max(0.0, b * b - c));
  }
  double best = std::numeric_limits<double>::infinity();
  const size_t n = z.polygon.size();
  for (size_t k = 0; k < n; ++k) {
    const glm::dvec2 a = z.polygon[k];
    const glm::dvec2 e = z.polygon[(k + 1) % n] - a;
    const double den = cross(d, e);
    if (den == 0.0) continue;
    const glm::dvec2 ao = a - o;
    const double t = cross(ao, e) / den;
    const double s = cross(ao, d) / den;
    if (t > 0.0 && s >= -1e-12 && s <= 1.0 + 1e-12) best = std::min(best, t);
  }
  return best;
}

}  // namespace

Status validate(const ParameterZone& z, glm::dvec2 uv) {
  if (z.shape == ParameterZone::Shape::kCircle) {
    if (!finite(z.centre) || !std::isfinite(z.radius))
      return Error("circle: values must be finite");
    if (!(z.radius > 0.0)) return Error("circle: radius must be positive");
    const glm::dvec2 d = uv - z.centre;
    if (!(std::sqrt(d.x * d.x + d.y * d.y) < z.radius)) {
      return Error("the constrained parameters (" + std::to_string(uv.x) + ", " +
                   std::to_string(uv.y) + ") are not inside the circle");
    }
    return {};
  }
  const size_t n = z.polygon.size();
  if (n < 3) return Error("polygon: needs at least 3 vertices, got " + std::to_string(n));
  double area = 0.0;
  for (size_t k = 0; k < n; ++k) {
    if (!finite(z.polygon[k]))
      return Error("polygon: vertex " + std::to_string(k) + " is not finite");
    area += cross(z.polygon[k], z.polygon[(k + 1) % n]);
  }
  if (area == 0.0) return Error("polygon: zero area");
  const double orientation = area > 0.0 ? 1.0 : -1.0;
  for (size_t k = 0; k < n; ++k) {
    const glm::dvec2 a = z.polygon[k];
    const glm::dvec2 b = z.polygon[(k + 1) % n];
    if (orientation * cross(b - a, uv - a) <= 0.0) {
      return Error("polygon: not star-shaped from the constrained parameters (" +
                   std::to_string(uv.x) + ", " + std::to_string(uv.y) + "): edge " +
                   std::to_string(k) + " is not seen from inside (or the point is outside)");
    }
  }
  return {};
}

double relative_radius(const ParameterZone& z, glm::dvec2 uv, glm::dvec2 point) {
  const glm::dvec2 d = point - uv;
  const double len = std::sqrt(d.x * d.x + d.y * d.y);
  if (len == 0.0) return 0.0;
  return len / exit_distance(z, uv, d / len);
}

std::pair<glm::dvec2, glm::dvec2> bounds(const ParameterZone& z) {
  if (z.shape == ParameterZone::Shape::kCircle) {
    return {z.centre - glm::dvec2(z.radius), z.centre + glm::dvec2(z.radius)};
  }
  glm::dvec2 lo = z.polygon.front();
  glm::dvec2 hi = lo;
  for (const glm::dvec2& p : z.polygon) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  return {lo, hi};
}

}  // namespace sculpt::core::nurbs
