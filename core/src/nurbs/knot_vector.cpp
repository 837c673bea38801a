// Basis functions after The NURBS Book (Piegl & Tiller), algorithms A2.1-A2.3.

#include "sculpt/core/nurbs/knot_vector.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace sculpt::core::nurbs {
namespace {

// The shortest of 15 or 17 significant digits that reads back as v.
std::string num(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.15g", v);
  if (std::strtod(text, nullptr) != v) std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

}  // namespace

Status validate_knots(std::span<const double> knots, int degree, int count) {
  if (degree < 1 || degree > kMaxDegree) {
    return Error("degree " + std::to_string(degree) + " is outside 1.." +
                 std::to_string(kMaxDegree));
  }
  if (count < degree + 1) {
    return Error(std::to_string(count) + " control points are too few for degree " +
                 std::to_string(degree) + " (at least " + std::to_string(degree + 1) + ")");
  }
  const size_t expected = static_cast<size_t>(count) + static_cast<size_t>(degree) + 1;
  if (knots.size() != expected) {
    return Error("expected " + std::to_string(expected) +
                 " knots (control points + degree + 1), got " + std::to_string(knots.size()));
  }
  for (size_t i = 0; i < knots.size(); ++i) {
    if (!std::isfinite(knots[i])) return Error("knots[" + std::to_string(i) + "] is not finite");
    if (i > 0 && knots[i] < knots[i - 1]) {
      return Error("knots[" + std::to_string(i) + "] = " + num(knots[i]) + " is below knots[" +
                   std::to_string(i - 1) + "] = " + num(knots[i - 1]) +
                   " (knots must be non-decreasing)");
    }
  }
  const size_t p = static_cast<size_t>(degree);
  for (size_t i = 1; i <= p; ++i) {
    if (knots[i] != knots[0]) {
      return Error("not clamped: the first " + std::to_string(p + 1) + " knots must be equal");
    }
    if (knots[knots.size() - 1 - i] != knots.back()) {
      return Error("not clamped: the last " + std::to_string(p + 1) + " knots must be equal");
    }
  }
  if (!(knots.back() > knots.front())) return Error("empty domain: all knots are equal");
  // Interior multiplicity above the degree would cut the curve in two.
  size_t run = 1;
  for (size_t i = p + 1; i + p + 1 < knots.size(); ++i) {
    run = knots[i] == knots[i - 1] && i > p + 1 ? run + 1 : 1;
    if (run > p) {
      return Error("interior knot " + num(knots[i]) + " repeated more than the degree (" +
                   std::to_string(degree) + ") times");
    }
  }
  return {};
}

int find_span(std::span<const double> knots, int degree, int count, double t) {
  const int n = count - 1;
  const double lo = knots[static_cast<size_t>(degree)];
  const double hi = knots[static_cast<size_t>(n + 1)];
  if (!(t > lo)) t = lo;  // also catches NaN
  if (t >= hi) {
    // The last non-empty span: skip trailing spans of zero length.
    int s = n;
    while (s > degree && knots[static_cast<size_t>(s)] == knots[static_cast<size_t>(s + 1)])
      --s;
    return s;
  }
  // Binary search for knots[s] <= t < knots[s+1], as A2.1.
  int low = degree;
  int high = n + 1;
  int mid = (low + high) / 2;
  while (t < knots[static_cast<size_t>(mid)] || t >= knots[static_cast<size_t>(mid + 1)]) {
    if (t < knots[static_cast<size_t>(mid)]) {
      high = mid;
    } else {
      low = mid;
    }
    mid = (low + high) / 2;
  }
  return mid;
}

void basis_functions(std::span<const double> knots, int degree, int span, double t, double* out) {
  std::array<double, kMaxDegree + 1> left{};
  std::array<double, kMaxDegree + 1> right{};
  out[0] = 1.0;
  for (int j = 1; j <= degree; ++j) {
    left[static_cast<size_t>(j)] = t - knots[static_cast<size_t>(span + 1 - j)];
    right[static_cast<size_t>(j)] = knots[static_cast<size_t>(span + j)] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp =
          out[r] / (right[static_cast<size_t>(r + 1)] + left[static_cast<size_t>(j - r)]);
      out[r] = saved + right[static_cast<size_t>(r + 1)] * temp;
      saved = left[static_cast<size_t>(j - r)] * temp;
    }
    out[j] = saved;
  }
}

void basis_derivatives(std::span<const double> knots, int degree, int span, double t, int order,
                       double* out) {
  const int p = degree;
  const size_t w = static_cast<size_t>(p + 1);
  std::array<double, (kMaxDegree + 1) * (kMaxDegree + 1)> ndu{};  // ndu[j * w + r]
  std::array<double, kMaxDegree + 1> left{};
  std::array<double, kMaxDegree + 1> right{};
  auto at = [&](int row, int col) -> double& {
    return ndu[static_cast<size_t>(row) * w + static_cast<size_t>(col)];
  };
  at(0, 0) = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[static_cast<size_t>(j)] = t - knots[static_cast<size_t>(span + 1 - j)];
    right[static_cast<size_t>(j)] = knots[static_cast<size_t>(span + j)] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      at(j, r) = right[static_cast<size_t>(r + 1)] + left[static_cast<size_t>(j - r)];
      const double temp = at(r, j - 1) / at(j, r);
      at(r, j) = saved + right[static_cast<size_t>(r + 1)] * temp;
      saved = left[static_cast<size_t>(j - r)] * temp;
    }
    at(j, j) = saved;
  }
  for (int j = 0; j <= p; ++j)
    out[j] = at(j, p);
  const int top = std::min(order, p);
  std::array<double, 2 * (kMaxDegree + 1)> a{};  // two rows of width p+1
  auto A = [&](int row, int col) -> double& {
    return a[static_cast<size_t>(row) * w + static_cast<size_t>(col)];
  };
  for (int r = 0; r <= p; ++r) {
    int s1 = 0;
    int s2 = 1;
    A(0, 0) = 1.0;
    for (int k = 1; k <= top; ++k) {
      double d = 0.0;
      const int rk = r - k;
      const int pk = p - k;
      if (r >= k) {
        A(s2, 0) = A(s1, 0) / at(pk + 1, rk);
        d = A(s2, 0) * at(rk, pk);
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = r - 1 <= pk ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        A(s2, j) = (A(s1, j) - A(s1, j - 1)) / at(pk + 1, rk + j);
        d += A(s2, j) * at(rk + j, pk);
      }
      if (r <= pk) {
        A(s2, k) = -A(s1, k - 1) / at(pk + 1, r);
        d += A(s2, k) * at(r, pk);
      }
      out[k * (p + 1) + r] = d;
      std::swap(s1, s2);
    }
  }
  int factor = p;
  for (int k = 1; k <= top; ++k) {
    for (int j = 0; j <= p; ++j)
      out[k * (p + 1) + j] *= factor;
    factor *= p - k;
  }
  for (int k = top + 1; k <= order; ++k) {
    for (int j = 0; j <= p; ++j)
      out[k * (p + 1) + j] = 0.0;
  }
}

std::vector<double> greville_abscissae(std::span<const double> knots, int degree) {
  const size_t count = knots.size() - static_cast<size_t>(degree) - 1;
  std::vector<double> g(count);
  for (size_t i = 0; i < count; ++i) {
    double sum = 0.0;
    for (size_t k = 1; k <= static_cast<size_t>(degree); ++k)
      sum += knots[i + k];
    g[i] = sum / degree;
  }
  return g;
}

std::vector<double> uniform_clamped_knots(int degree, int count, double lo, double hi) {
  assert(degree >= 1 && count >= degree + 1);
  std::vector<double> knots;
  knots.reserve(static_cast<size_t>(count + degree + 1));
  for (int i = 0; i <= degree; ++i)
    knots.push_back(lo);
  const int interior = count - degree - 1;
  for (int i = 1; i <= interior; ++i)
    knots.push_back(lo + (hi - lo) * i / (interior + 1));
  for (int i = 0; i <= degree; ++i)
    knots.push_back(hi);
  return knots;
}

std::vector<double> breakpoints(std::span<const double> knots, int degree, int count) {
  std::vector<double> b;
  for (int i = degree; i <= count; ++i) {
    const double k = knots[static_cast<size_t>(i)];
    if (b.empty() || k != b.back()) b.push_back(k);
  }
  return b;
}

}  // namespace sculpt::core::nurbs
