// Surface evaluation after The NURBS Book: homogeneous derivatives (A3.6)
// turned into rational ones (A4.4); refinement row by row (A5.5 is A5.4
// applied to every row or column of homogeneous points).

#include "sculpt/core/nurbs/nurbs_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "nurbs/knot_refinement.h"
#include "sculpt/core/nurbs/nurbs_limits.h"

namespace sculpt::core::nurbs {
namespace {

constexpr size_t kW = kMaxDegree + 1;

}  // namespace

bool NurbsSurface::rational() const {
  return std::any_of(weights.begin(), weights.end(), [](double w) { return w != 1.0; });
}

Status validate(const NurbsSurface& s) {
  if (s.count_u < 1 || s.count_v < 1) return Error("count_u and count_v must be positive");
  if (Status st = validate_knots(s.knots_u, s.degree_u, s.count_u); !st) {
    return Error("knots_u / degree_u: " + st.error().message());
  }
  if (Status st = validate_knots(s.knots_v, s.degree_v, s.count_v); !st) {
    return Error("knots_v / degree_v: " + st.error().message());
  }
  const size_t expected = static_cast<size_t>(s.count_u) * static_cast<size_t>(s.count_v);
  if (s.points.size() != expected) {
    return Error("expected " + std::to_string(expected) + " control points (count_u " +
                 std::to_string(s.count_u) + " x count_v " + std::to_string(s.count_v) + "), got " +
                 std::to_string(s.points.size()));
  }
  if (Status st = check_control_points(s.points); !st) return st;
  return check_weights(s.weights, expected);
}

namespace {

// Knot spans and the non-zero basis values of both directions at (u, v),
// parameters clamped to the domain.
struct LocalBasis {
  int span_u = 0, span_v = 0;
  std::array<double, kW> nu{}, nv{};
};

LocalBasis local_basis(const NurbsSurface& s, double u, double v) {
  LocalBasis b;
  b.span_u = find_span(s.knots_u, s.degree_u, s.count_u, u);
  b.span_v = find_span(s.knots_v, s.degree_v, s.count_v, v);
  basis_functions(s.knots_u, s.degree_u, b.span_u, std::clamp(u, s.u_min(), s.u_max()),
                  b.nu.data());
  basis_functions(s.knots_v, s.degree_v, b.span_v, std::clamp(v, s.v_min(), s.v_max()),
                  b.nv.data());
  return b;
}

}  // namespace

glm::dvec3 evaluate(const NurbsSurface& s, double u, double v) {
  const int p = s.degree_u;
  const int q = s.degree_v;
  const LocalBasis lb = local_basis(s, u, v);
  glm::dvec4 sum(0.0);
  for (int b = 0; b <= q; ++b) {
    glm::dvec4 row(0.0);
    const int j = lb.span_v - q + b;
    for (int a = 0; a <= p; ++a) {
      row += lb.nu[static_cast<size_t>(a)] * homogeneous(s, s.index(lb.span_u - p + a, j));
    }
    sum += lb.nv[static_cast<size_t>(b)] * row;
  }
  return glm::dvec3(sum) / sum.w;
}

SurfaceDerivatives derivatives(const NurbsSurface& s, double u, double v, int order) {
  const int p = s.degree_u;
  const int q = s.degree_v;
  const int d = std::clamp(order, 0, 2);
  const int su = find_span(s.knots_u, p, s.count_u, u);
  const int sv = find_span(s.knots_v, q, s.count_v, v);
  u = std::clamp(u, s.u_min(), s.u_max());
  v = std::clamp(v, s.v_min(), s.v_max());
  std::array<double, 3 * kW> nu{};
  std::array<double, 3 * kW> nv{};
  basis_derivatives(s.knots_u, p, su, u, d, nu.data());
  basis_derivatives(s.knots_v, q, sv, v, d, nv.data());
  // aw[k][l]: homogeneous derivative d^(k+l) / du^k dv^l (A3.6).
  std::array<std::array<glm::dvec4, 3>, 3> aw{};
  for (int k = 0; k <= d; ++k) {
    for (int l = 0; k + l <= d; ++l) {
      glm::dvec4 sum(0.0);
      for (int b = 0; b <= q; ++b) {
        glm::dvec4 row(0.0);
        for (int a = 0; a <= p; ++a) {
          row += nu[static_cast<size_t>(k * (p + 1) + a)] *
                 homogeneous(s, s.index(su - p + a, sv - q + b));
        }
        sum += nv[static_cast<size_t>(l * (q + 1) + b)] * row;
      }
      aw[static_cast<size_t>(k)][static_cast<size_t>(l)] = sum;
    }
  }
  // A4.4 with binomials of order <= 2 written out.
  auto A = [&](int k, int l) {
    return glm::dvec3(aw[static_cast<size_t>(k)][static_cast<size_t>(l)]);
  };
  auto W = [&](int k, int l) { return aw[static_cast<size_t>(k)][static_cast<size_t>(l)].w; };
  const double w = W(0, 0);
  SurfaceDerivatives r;
  r.s = A(0, 0) / w;
  if (d >= 1) {
    r.su = (A(1, 0) - W(1, 0) * r.s) / w;
    r.sv = (A(0, 1) - W(0, 1) * r.s) / w;
  }
  if (d >= 2) {
    r.suu = (A(2, 0) - 2.0 * W(1, 0) * r.su - W(2, 0) * r.s) / w;
    r.svv = (A(0, 2) - 2.0 * W(0, 1) * r.sv - W(0, 2) * r.s) / w;
    r.suv = (A(1, 1) - W(1, 0) * r.sv - W(0, 1) * r.su - W(1, 1) * r.s) / w;
  }
  return r;
}

glm::dvec3 normal(const NurbsSurface& s, double u, double v) {
  const SurfaceDerivatives d = derivatives(s, u, v, 1);
  glm::dvec3 n = glm::cross(d.su, d.sv);
  const double len = glm::length(n);
  const double scale = glm::length(d.su) * glm::length(d.sv);
  if (len > 1e-12 * scale && len > 0.0) return n / len;
  // A collapsed edge (e.g. a pole): take the normal just inside the domain.
  const double eu = 1e-6 * (s.u_max() - s.u_min());
  const double ev = 1e-6 * (s.v_max() - s.v_min());
  const double uc = std::clamp(u, s.u_min() + eu, s.u_max() - eu);
  const double vc = std::clamp(v, s.v_min() + ev, s.v_max() - ev);
  const SurfaceDerivatives e = derivatives(s, uc, vc, 1);
  n = glm::cross(e.su, e.sv);
  const double l2 = glm::length(n);
  return l2 > 0.0 ? n / l2 : glm::dvec3(0.0, 0.0, 1.0);
}

RationalBasis rational_basis(const NurbsSurface& s, double u, double v) {
  const int p = s.degree_u;
  const int q = s.degree_v;
  const LocalBasis lb = local_basis(s, u, v);
  const int su = lb.span_u;
  const int sv = lb.span_v;
  const std::array<double, kW>& nu = lb.nu;
  const std::array<double, kW>& nv = lb.nv;
  RationalBasis r;
  r.first_i = su - p;
  r.first_j = sv - q;
  r.width_u = p + 1;
  r.width_v = q + 1;
  r.values.resize(static_cast<size_t>((p + 1) * (q + 1)));
  double sum = 0.0;
  for (int b = 0; b <= q; ++b) {
    for (int a = 0; a <= p; ++a) {
      const double value = nu[static_cast<size_t>(a)] * nv[static_cast<size_t>(b)] *
                           s.weight(s.index(r.first_i + a, r.first_j + b));
      r.values[static_cast<size_t>(a + (p + 1) * b)] = value;
      sum += value;
    }
  }
  for (double& value : r.values)
    value /= sum;
  return r;
}

std::vector<double> rational_basis_dense(const NurbsSurface& s, double u, double v) {
  std::vector<double> dense(static_cast<size_t>(s.point_count()), 0.0);
  const RationalBasis r = rational_basis(s, u, v);
  for (int b = 0; b < r.width_v; ++b) {
    for (int a = 0; a < r.width_u; ++a) {
      dense[static_cast<size_t>(s.index(r.first_i + a, r.first_j + b))] =
          r.values[static_cast<size_t>(a + r.width_u * b)];
    }
  }
  return dense;
}

namespace {

// Refines every row (along u) or column (along v) of homogeneous points.
NurbsSurface refine_direction(const NurbsSurface& s, std::span<const double> x, bool along_u) {
  if (x.empty()) return s;
  const int p = along_u ? s.degree_u : s.degree_v;
  const std::vector<double>& knots = along_u ? s.knots_u : s.knots_v;
  const int rows = along_u ? s.count_v : s.count_u;
  const int len = along_u ? s.count_u : s.count_v;
  NurbsSurface out = s;
  const int new_len = len + static_cast<int>(x.size());
  (along_u ? out.count_u : out.count_v) = new_len;
  const size_t total = static_cast<size_t>(new_len) * static_cast<size_t>(rows);
  out.points.assign(total, glm::dvec3(0.0));
  const bool rational = s.rational();
  out.weights.assign(rational ? total : 0, 1.0);
  std::vector<glm::dvec4> row(static_cast<size_t>(len));
  std::vector<glm::dvec4> refined;
  std::vector<double> new_knots;
  for (int r = 0; r < rows; ++r) {
    for (int k = 0; k < len; ++k) {
      row[static_cast<size_t>(k)] = homogeneous(s, along_u ? s.index(k, r) : s.index(r, k));
    }
    detail::refine_row(p, knots, row, x, new_knots, refined);
    for (int k = 0; k < new_len; ++k) {
      const int idx = along_u ? out.index(k, r) : out.index(r, k);
      const glm::dvec4 q = refined[static_cast<size_t>(k)];
      out.points[static_cast<size_t>(idx)] = glm::dvec3(q) / q.w;
      if (rational) out.weights[static_cast<size_t>(idx)] = q.w;
    }
  }
  (along_u ? out.knots_u : out.knots_v) = new_knots;
  return out;
}

}  // namespace

NurbsSurface refine_u(const NurbsSurface& s, std::span<const double> new_knots) {
  return refine_direction(s, new_knots, true);
}

NurbsSurface refine_v(const NurbsSurface& s, std::span<const double> new_knots) {
  return refine_direction(s, new_knots, false);
}

std::vector<double> greville_u(const NurbsSurface& s) {
  return greville_abscissae(s.knots_u, s.degree_u);
}
std::vector<double> greville_v(const NurbsSurface& s) {
  return greville_abscissae(s.knots_v, s.degree_v);
}

NurbsSurface flat_sheet(int count_u, int count_v, int degree_u, int degree_v, double size_x,
                        double size_y) {
  NurbsSurface s;
  s.degree_u = degree_u;
  s.degree_v = degree_v;
  s.count_u = count_u;
  s.count_v = count_v;
  s.knots_u = uniform_clamped_knots(degree_u, count_u);
  s.knots_v = uniform_clamped_knots(degree_v, count_v);
  const std::vector<double> gu = greville_u(s);
  const std::vector<double> gv = greville_v(s);
  s.points.resize(static_cast<size_t>(count_u * count_v));
  for (int j = 0; j < count_v; ++j) {
    for (int i = 0; i < count_u; ++i) {
      s.point(i, j) = {gu[static_cast<size_t>(i)] * size_x, gv[static_cast<size_t>(j)] * size_y,
                       0.0};
    }
  }
  return s;
}

NurbsSurface example_sheet() {
  NurbsSurface s = flat_sheet(15, 10, 3, 3, 140.0, 90.0);
  const double pi = std::numbers::pi;
  for (glm::dvec3& point : s.points) {
    point.z = 6.0 * std::sin(2.0 * pi * point.x / 140.0) * std::cos(pi * point.y / 90.0);
    // sin(pi) is 1.2e-16 in doubles: keep the files readable.
    if (std::abs(point.z) < 1e-12) point.z = 0.0;
  }
  return s;
}

}  // namespace sculpt::core::nurbs
