#include "nurbs/knot_refinement.h"

#include <cassert>

#include "sculpt/core/nurbs/knot_vector.h"

namespace sculpt::core::nurbs::detail {

void refine_row(int p, std::span<const double> knots, std::span<const glm::dvec4> points,
                std::span<const double> inserted, std::vector<double>& new_knots,
                std::vector<glm::dvec4>& out) {
  const int n = static_cast<int>(points.size()) - 1;
  const int m = n + p + 1;
  const int r = static_cast<int>(inserted.size()) - 1;
  new_knots.assign(knots.size() + inserted.size(), 0.0);
  out.assign(points.size() + inserted.size(), glm::dvec4(0.0));
  if (r < 0) {
    new_knots.assign(knots.begin(), knots.end());
    out.assign(points.begin(), points.end());
    return;
  }
  auto U = [&](int i) { return knots[static_cast<size_t>(i)]; };
  auto X = [&](int i) { return inserted[static_cast<size_t>(i)]; };
  auto Ub = [&](int i) -> double& { return new_knots[static_cast<size_t>(i)]; };
  auto Q = [&](int i) -> glm::dvec4& { return out[static_cast<size_t>(i)]; };
  auto P = [&](int i) { return points[static_cast<size_t>(i)]; };
  assert(X(0) > U(p) && X(r) < U(n + 1));

  const int a = find_span(knots, p, n + 1, X(0));
  const int b = find_span(knots, p, n + 1, X(r)) + 1;
  for (int j = 0; j <= a - p; ++j)
    Q(j) = P(j);
  for (int j = b - 1; j <= n; ++j)
    Q(j + r + 1) = P(j);
  for (int j = 0; j <= a; ++j)
    Ub(j) = U(j);
  for (int j = b + p; j <= m; ++j)
    Ub(j + r + 1) = U(j);
  int i = b + p - 1;
  int k = b + p + r;
  for (int j = r; j >= 0; --j) {
    while (X(j) <= U(i) && i > a) {
      Q(k - p - 1) = P(i - p - 1);
      Ub(k) = U(i);
      --k;
      --i;
    }
    Q(k - p - 1) = Q(k - p);
    for (int l = 1; l <= p; ++l) {
      const int ind = k - p + l;
      double alpha = Ub(k + l) - X(j);
      if (alpha == 0.0) {
        Q(ind - 1) = Q(ind);
      } else {
        alpha /= Ub(k + l) - U(i - p + l);
        Q(ind - 1) = alpha * Q(ind - 1) + (1.0 - alpha) * Q(ind);
      }
    }
    Ub(k) = X(j);
    --k;
  }
}

}  // namespace sculpt::core::nurbs::detail
