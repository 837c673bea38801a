// Localisation constraints of La Greca, Raffin & Gesquière §4.2.

#include "sculpt/core/nurbs/influence.h"

#include <algorithm>
#include <cmath>

namespace sculpt::core::nurbs {
namespace {

void normalise(std::vector<double>& f) {
  const double top = *std::max_element(f.begin(), f.end());
  if (top > 0.0) {
    for (double& x : f)
      x /= top;
  }
}

// The zone's profile: high near (u, v), low near the border, C1 at both.
double profile(double rho) {
  return rho >= 1.0 ? 0.0 : 1.0 - rho * rho * (3.0 - 2.0 * rho);
}

}  // namespace

std::vector<double> natural_influence(const NurbsSurface& s, double u, double v) {
  std::vector<double> f = rational_basis_dense(s, u, v);
  normalise(f);
  return f;
}

std::vector<double> gaussian_influence(const NurbsSurface& s, double u, double v,
                                       double radius_index) {
  if (!(radius_index > 0.0)) return natural_influence(s, u, v);
  const RationalBasis r = rational_basis(s, u, v);
  const double sigma = radius_index / 3.0;
  const int reach = static_cast<int>(std::floor(radius_index));
  std::vector<double> f(static_cast<size_t>(s.point_count()), 0.0);
  // Only the (p+1)(q+1) non-zero basis values contribute: scatter each one.
  for (int b = 0; b < r.width_v; ++b) {
    for (int a = 0; a < r.width_u; ++a) {
      const double value = r.values[static_cast<size_t>(a + r.width_u * b)];
      if (value == 0.0) continue;
      const int ci = r.first_i + a;
      const int cj = r.first_j + b;
      for (int j = std::max(0, cj - reach); j <= std::min(s.count_v - 1, cj + reach); ++j) {
        for (int i = std::max(0, ci - reach); i <= std::min(s.count_u - 1, ci + reach); ++i) {
          const double d2 = static_cast<double>((i - ci) * (i - ci) + (j - cj) * (j - cj));
          if (d2 > radius_index * radius_index) continue;
          f[static_cast<size_t>(s.index(i, j))] += value * std::exp(-d2 / (2.0 * sigma * sigma));
        }
      }
    }
  }
  normalise(f);
  return f;
}

double influence_at(const NurbsSurface& s, double u, double v, const std::vector<double>& f) {
  const RationalBasis r = rational_basis(s, u, v);
  double sum = 0.0;
  for (int b = 0; b < r.width_v; ++b) {
    for (int a = 0; a < r.width_u; ++a) {
      sum += r.values[static_cast<size_t>(a + r.width_u * b)] *
             f[static_cast<size_t>(s.index(r.first_i + a, r.first_j + b))];
    }
  }
  return sum;
}

Result<std::vector<double>> zone_influence(const NurbsSurface& s, double u, double v,
                                           const ParameterZone& zone) {
  const glm::dvec2 uv(u, v);
  if (Status st = validate(zone, uv); !st) return st.error();
  const std::vector<double> gu = greville_u(s);
  const std::vector<double> gv = greville_v(s);
  std::vector<double> f(static_cast<size_t>(s.point_count()), 0.0);
  for (int j = 0; j < s.count_v; ++j) {
    for (int i = 0; i < s.count_u; ++i) {
      const glm::dvec2 g(gu[static_cast<size_t>(i)], gv[static_cast<size_t>(j)]);
      f[static_cast<size_t>(s.index(i, j))] = profile(relative_radius(zone, uv, g));
    }
  }
  if (!(influence_at(s, u, v, f) > 0.0)) {
    return Error("the zone holds no control point that influences (u, v) = (" + std::to_string(u) +
                 ", " + std::to_string(v) +
                 "): none of the parametric images of its control points lies inside; enlarge "
                 "the zone or refine");
  }
  normalise(f);
  return f;
}

int control_points_in_zone(const NurbsSurface& s, double u, double v, const ParameterZone& zone) {
  const std::vector<double> gu = greville_u(s);
  const std::vector<double> gv = greville_v(s);
  int count = 0;
  for (double y : gv) {
    for (double x : gu)
      count += relative_radius(zone, {u, v}, {x, y}) < 1.0;
  }
  return count;
}

namespace {

// Midpoints of the non-empty knot spans of `knots` meeting [lo, hi].
std::vector<double> midpoints_in(const std::vector<double>& knots, int degree, int count, double lo,
                                 double hi) {
  std::vector<double> x;
  for (int s = degree; s < count; ++s) {
    const double a = knots[static_cast<size_t>(s)];
    const double b = knots[static_cast<size_t>(s + 1)];
    if (a < b && b > lo && a < hi) x.push_back(0.5 * (a + b));
  }
  return x;
}

}  // namespace

Result<NurbsSurface> refine_in_zone(const NurbsSurface& surface, double u, double v,
                                    const ParameterZone& zone, int min_points, int max_points) {
  NurbsSurface s = surface;
  const auto [lo, hi] = bounds(zone);
  for (;;) {
    const int inside = control_points_in_zone(s, u, v, zone);
    const bool influences = zone_influence(s, u, v, zone).ok();
    if (inside >= min_points && influences) return s;
    const std::vector<double> xu = midpoints_in(s.knots_u, s.degree_u, s.count_u, lo.x, hi.x);
    const std::vector<double> xv = midpoints_in(s.knots_v, s.degree_v, s.count_v, lo.y, hi.y);
    if (xu.empty() && xv.empty()) return Error("refinement: the zone meets no knot span");
    const int64_t next = static_cast<int64_t>(s.count_u + static_cast<int>(xu.size())) *
                         (s.count_v + static_cast<int>(xv.size()));
    if (next > max_points) {
      return Error("refinement: the zone holds " + std::to_string(inside) +
                   " control points of the " + std::to_string(min_points) +
                   " asked for, and one more halving would make " + std::to_string(next) +
                   " control points (limit " + std::to_string(max_points) + ")");
    }
    s = refine_v(refine_u(s, xu), xv);
  }
}

}  // namespace sculpt::core::nurbs
