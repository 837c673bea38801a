// Curve evaluation after The NURBS Book: homogeneous derivatives (A3.2) turned
// into rational ones (A4.2); knot insertion as Boehm refinement (A5.4).

#include "sculpt/core/nurbs/nurbs_curve.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

#include "nurbs/knot_refinement.h"
#include "sculpt/core/nurbs/knot_vector.h"
#include "sculpt/core/nurbs/nurbs_limits.h"

namespace sculpt::core::nurbs {
namespace {

double binomial(int n, int k) {
  double b = 1.0;
  for (int i = 1; i <= k; ++i)
    b = b * (n - k + i) / i;
  return b;
}

}  // namespace

bool NurbsCurve::rational() const {
  return std::any_of(weights.begin(), weights.end(), [](double w) { return w != 1.0; });
}

Status validate(const NurbsCurve& curve) {
  if (Status st = validate_knots(curve.knots, curve.degree, curve.count()); !st) {
    return Error("knots: " + st.error().message());
  }
  if (Status st = check_control_points(curve.points); !st) return st;
  return check_weights(curve.weights, curve.points.size());
}

glm::dvec3 evaluate(const NurbsCurve& curve, double t) {
  const int p = curve.degree;
  const int span = find_span(curve.knots, p, curve.count(), t);
  t = std::clamp(t, curve.domain_min(), curve.domain_max());
  std::array<double, kMaxDegree + 1> n{};
  basis_functions(curve.knots, p, span, t, n.data());
  glm::dvec4 c(0.0);
  for (int j = 0; j <= p; ++j) {
    const int k = span - p + j;
    const double w = curve.weight(k);
    c += n[static_cast<size_t>(j)] * glm::dvec4(curve.points[static_cast<size_t>(k)] * w, w);
  }
  return glm::dvec3(c) / c.w;
}

std::vector<glm::dvec3> derivatives(const NurbsCurve& curve, double t, int order) {
  const int p = curve.degree;
  const int span = find_span(curve.knots, p, curve.count(), t);
  t = std::clamp(t, curve.domain_min(), curve.domain_max());
  std::vector<double> nd(static_cast<size_t>((order + 1) * (p + 1)));
  basis_derivatives(curve.knots, p, span, t, order, nd.data());
  std::vector<glm::dvec4> cw(static_cast<size_t>(order + 1), glm::dvec4(0.0));
  for (int k = 0; k <= order; ++k) {
    for (int j = 0; j <= p; ++j) {
      const int i = span - p + j;
      const double w = curve.weight(i);
      cw[static_cast<size_t>(k)] += nd[static_cast<size_t>(k * (p + 1) + j)] *
                                    glm::dvec4(curve.points[static_cast<size_t>(i)] * w, w);
    }
  }
  std::vector<glm::dvec3> ck(static_cast<size_t>(order + 1));
  for (int k = 0; k <= order; ++k) {
    glm::dvec3 v(cw[static_cast<size_t>(k)]);
    for (int i = 1; i <= k; ++i) {
      v -= binomial(k, i) * cw[static_cast<size_t>(i)].w * ck[static_cast<size_t>(k - i)];
    }
    ck[static_cast<size_t>(k)] = v / cw[0].w;
  }
  return ck;
}

NurbsCurve refine(const NurbsCurve& curve, std::span<const double> new_knots) {
  std::vector<glm::dvec4> pw(curve.points.size());
  for (size_t i = 0; i < pw.size(); ++i) {
    const double w = curve.weight(static_cast<int>(i));
    pw[i] = glm::dvec4(curve.points[i] * w, w);
  }
  NurbsCurve out;
  out.degree = curve.degree;
  std::vector<glm::dvec4> qw;
  detail::refine_row(curve.degree, curve.knots, pw, new_knots, out.knots, qw);
  out.points.resize(qw.size());
  const bool rational = curve.rational();
  if (rational) out.weights.resize(qw.size());
  for (size_t i = 0; i < qw.size(); ++i) {
    out.points[i] = glm::dvec3(qw[i]) / qw[i].w;
    if (rational) out.weights[i] = qw[i].w;
  }
  return out;
}

NurbsCurve insert_knot(const NurbsCurve& curve, double t, int times) {
  const std::vector<double> x(static_cast<size_t>(times), t);
  return refine(curve, x);
}

NurbsCurve straight_curve(glm::dvec3 a, glm::dvec3 b, int degree, int count) {
  NurbsCurve c;
  c.degree = degree;
  c.knots = uniform_clamped_knots(degree, count);
  for (double g : greville_abscissae(c.knots, degree))
    c.points.push_back(a + g * (b - a));
  return c;
}

}  // namespace sculpt::core::nurbs
