#pragma once
// What a NURBS curve or surface read from outside may hold (docs/formats.md):
// every coordinate within +-kMaxCoordinate and every weight in
// [kMinWeight, kMaxWeight]. Finite alone is not enough: a weight of 1e308
// times a coordinate overflows the homogeneous point to infinity, and the
// evaluation then writes NaN. Within these bounds w * P and the basis sums
// stay far from overflow (1e18 at most), so every value evaluated or
// written is finite.

#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/base/result.h"

namespace sculpt::core::nurbs {

inline constexpr double kMaxCoordinate = 1e9;
inline constexpr double kMinWeight = 1e-9;
inline constexpr double kMaxWeight = 1e9;

/// Every control point's coordinates finite and within +-kMaxCoordinate.
Status check_control_points(const std::vector<glm::dvec3>& points);
/// No weights (all 1), or one per control point, each in [kMinWeight, kMaxWeight].
Status check_weights(const std::vector<double>& weights, size_t control_points);

}  // namespace sculpt::core::nurbs
