#include "sculpt/core/nurbs/punctual_constraint.h"

#include "sculpt/core/nurbs/influence.h"

namespace sculpt::core::nurbs {

Result<std::vector<int>> apply_linear_constraint(NurbsSurface& s, double u, double v,
                                                 glm::dvec3 target, std::span<const double> f) {
  if (f.size() != static_cast<size_t>(s.point_count())) {
    return Error("influence has " + std::to_string(f.size()) + " values for " +
                 std::to_string(s.point_count()) + " control points");
  }
  const RationalBasis r = rational_basis(s, u, v);
  double denominator = 0.0;
  for (int b = 0; b < r.width_v; ++b) {
    for (int a = 0; a < r.width_u; ++a) {
      denominator += r.values[static_cast<size_t>(a + r.width_u * b)] *
                     f[static_cast<size_t>(s.index(r.first_i + a, r.first_j + b))];
    }
  }
  if (!(denominator > 0.0)) {
    return Error("no control point with a non-zero influence acts on S(u, v)");
  }
  const glm::dvec3 e = target - evaluate(s, u, v);
  std::vector<int> moved;
  for (int k = 0; k < s.point_count(); ++k) {
    const double fk = f[static_cast<size_t>(k)];
    if (fk > 0.0) {
      s.points[static_cast<size_t>(k)] += (fk / denominator) * e;
      moved.push_back(k);
    }
  }
  return moved;
}

}  // namespace sculpt::core::nurbs
