// Global interpolation (A9.1) and least-squares approximation (A9.7) of The
// NURBS Book. The systems are small (a device path gives a few hundred
// samples), so Eigen's dense solvers are used; QR on the collocation matrix
// rather than the normal equations keeps the least squares well conditioned.

#include "sculpt/core/nurbs/curve_fitting.h"

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "sculpt/core/nurbs/knot_vector.h"

namespace sculpt::core::nurbs {
namespace {

// Chord-length parameters (Eq. 9.5) on [0, 1].
std::vector<double> chord_parameters(std::span<const glm::dvec3> q) {
  std::vector<double> t(q.size(), 0.0);
  double total = 0.0;
  for (size_t k = 1; k < q.size(); ++k)
    total += glm::length(q[k] - q[k - 1]);
  double acc = 0.0;
  for (size_t k = 1; k < q.size(); ++k) {
    acc += glm::length(q[k] - q[k - 1]);
    t[k] = acc / total;
  }
  t.back() = 1.0;
  return t;
}

// A curve of `count` control points and degree p whose knot vector is
// clamped to [0, 1]; the interior knots are left for the caller to set.
NurbsCurve clamped_frame(int count, int p) {
  NurbsCurve c;
  c.degree = p;
  c.knots.assign(static_cast<size_t>(count + p + 1), 0.0);
  for (int j = 0; j <= p; ++j)
    c.knots[static_cast<size_t>(count + j)] = 1.0;
  return c;
}

Status check_points(std::span<const glm::dvec3> q, size_t needed, int degree, const char* what) {
  if (degree < 1 || degree > kMaxDegree) {
    return Error("degree " + std::to_string(degree) + " is outside 1.." +
                 std::to_string(kMaxDegree));
  }
  for (size_t k = 0; k < q.size(); ++k) {
    if (!std::isfinite(q[k].x) || !std::isfinite(q[k].y) || !std::isfinite(q[k].z)) {
      return Error(std::string(what) + ": point " + std::to_string(k) + " is not finite");
    }
  }
  if (q.size() < needed) {
    return Error(std::string(what) + ": " + std::to_string(q.size()) +
                 " points are too few (at least " + std::to_string(needed) + ")");
  }
  return {};
}

}  // namespace

Result<NurbsCurve> interpolate_curve(std::span<const glm::dvec3> q, int degree) {
  if (Status st =
          check_points(q, static_cast<size_t>(std::max(degree, 1)) + 1, degree, "interpolation");
      !st) {
    return st.error();
  }
  for (size_t k = 1; k < q.size(); ++k) {
    if (q[k] == q[k - 1]) {
      return Error("interpolation: points " + std::to_string(k - 1) + " and " + std::to_string(k) +
                   " are equal");
    }
  }
  const int n = static_cast<int>(q.size()) - 1;
  const int p = degree;
  const std::vector<double> t = chord_parameters(q);
  NurbsCurve c = clamped_frame(n + 1, p);
  for (int j = 1; j <= n - p; ++j) {
    double sum = 0.0;
    for (int i = j; i < j + p; ++i)
      sum += t[static_cast<size_t>(i)];
    c.knots[static_cast<size_t>(j + p)] = sum / p;
  }
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n + 1, n + 1);
  Eigen::MatrixXd b(n + 1, 3);
  std::array<double, kMaxDegree + 1> nb{};
  for (int k = 0; k <= n; ++k) {
    const double tk = t[static_cast<size_t>(k)];
    const int span = find_span(c.knots, p, n + 1, tk);
    basis_functions(c.knots, p, span, tk, nb.data());
    for (int j = 0; j <= p; ++j)
      a(k, span - p + j) = nb[static_cast<size_t>(j)];
    b.row(k) << q[static_cast<size_t>(k)].x, q[static_cast<size_t>(k)].y,
        q[static_cast<size_t>(k)].z;
  }
  const Eigen::MatrixXd x = a.partialPivLu().solve(b);
  c.points.resize(static_cast<size_t>(n + 1));
  for (int i = 0; i <= n; ++i)
    c.points[static_cast<size_t>(i)] = {x(i, 0), x(i, 1), x(i, 2)};
  return c;
}

Result<NurbsCurve> fit_curve(std::span<const glm::dvec3> points, int degree, int control_points) {
  std::vector<glm::dvec3> q;
  q.reserve(points.size());
  for (const glm::dvec3& p : points) {
    if (q.empty() || p != q.back()) q.push_back(p);
  }
  if (Status st = check_points(points, 2, degree, "fit"); !st) return st.error();
  if (control_points < degree + 1) {
    return Error("fit: " + std::to_string(control_points) +
                 " control points are too few for degree " + std::to_string(degree));
  }
  if (static_cast<size_t>(control_points) > q.size()) {
    return Error("fit: " + std::to_string(control_points) +
                 " control points need as many distinct points, got " + std::to_string(q.size()));
  }
  if (static_cast<size_t>(control_points) == q.size()) return interpolate_curve(q, degree);
  const int m = static_cast<int>(q.size()) - 1;
  const int n = control_points - 1;
  const int p = degree;
  const std::vector<double> t = chord_parameters(q);
  NurbsCurve c = clamped_frame(n + 1, p);
  // Eq. 9.69: every knot span holds at least one parameter, so the system
  // is positive definite (Schoenberg-Whitney).
  const double d = static_cast<double>(m + 1) / (n - p + 1);
  for (int j = 1; j <= n - p; ++j) {
    const int i = static_cast<int>(j * d);
    const double alpha = j * d - i;
    c.knots[static_cast<size_t>(p + j)] =
        (1.0 - alpha) * t[static_cast<size_t>(i - 1)] + alpha * t[static_cast<size_t>(i)];
  }
  c.points.assign(static_cast<size_t>(n + 1), glm::dvec3(0.0));
  c.points.front() = q.front();
  c.points.back() = q.back();
  if (n >= 2) {
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(m - 1, n - 1);
    Eigen::MatrixXd r(m - 1, 3);
    std::array<double, kMaxDegree + 1> nb{};
    for (int k = 1; k < m; ++k) {
      const double tk = t[static_cast<size_t>(k)];
      const int span = find_span(c.knots, p, n + 1, tk);
      basis_functions(c.knots, p, span, tk, nb.data());
      double n0 = 0.0;
      double nn = 0.0;
      for (int j = 0; j <= p; ++j) {
        const int i = span - p + j;
        const double value = nb[static_cast<size_t>(j)];
        if (i == 0) {
          n0 = value;
        } else if (i == n) {
          nn = value;
        } else {
          a(k - 1, i - 1) = value;
        }
      }
      const glm::dvec3 rk = q[static_cast<size_t>(k)] - n0 * q.front() - nn * q.back();
      r.row(k - 1) << rk.x, rk.y, rk.z;
    }
    const Eigen::MatrixXd x = a.colPivHouseholderQr().solve(r);
    for (int i = 1; i < n; ++i)
      c.points[static_cast<size_t>(i)] = {x(i - 1, 0), x(i - 1, 1), x(i - 1, 2)};
  }
  return c;
}

}  // namespace sculpt::core::nurbs
