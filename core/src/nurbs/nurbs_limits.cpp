#include "sculpt/core/nurbs/nurbs_limits.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace sculpt::core::nurbs {

namespace {

std::string short_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

bool within(double v, double limit) {
  return std::isfinite(v) && std::fabs(v) <= limit;
}

}  // namespace

Status check_control_points(const std::vector<glm::dvec3>& points) {
  for (size_t i = 0; i < points.size(); ++i) {
    const glm::dvec3& p = points[i];
    if (!within(p.x, kMaxCoordinate) || !within(p.y, kMaxCoordinate) ||
        !within(p.z, kMaxCoordinate)) {
      return Error("control_points[" + std::to_string(i) + "] = (" + short_number(p.x) + ", " +
                   short_number(p.y) + ", " + short_number(p.z) + ") is not within +-" +
                   short_number(kMaxCoordinate));
    }
  }
  return {};
}

Status check_weights(const std::vector<double>& weights, size_t control_points) {
  if (weights.empty()) return {};
  if (weights.size() != control_points) {
    return Error("expected " + std::to_string(control_points) +
                 " weights (one per control point), got " + std::to_string(weights.size()));
  }
  for (size_t i = 0; i < weights.size(); ++i) {
    const double w = weights[i];
    if (!(w >= kMinWeight && w <= kMaxWeight)) {
      return Error("weights[" + std::to_string(i) + "] = " + short_number(w) + " is not in [" +
                   short_number(kMinWeight) + ", " + short_number(kMaxWeight) + "]");
    }
  }
  return {};
}

}  // namespace sculpt::core::nurbs
