#pragma once
// B-spline basis functions on clamped knot vectors (The NURBS Book, Piegl &
// Tiller, 2nd ed., chapter 2) and the knot-vector checks every curve and
// surface runs on its input.
//
// A knot vector of a degree-p basis with n functions holds n + p + 1
// non-decreasing values; "clamped" means the first p + 1 and the last p + 1
// are equal, so the curve or surface starts and ends at its end control
// points. The domain is [knots[p], knots[n]].

#include <span>
#include <string>
#include <vector>

#include "sculpt/base/result.h"

namespace sculpt::core::nurbs {

/// Largest degree accepted from outside: far beyond any modelling use, small
/// enough for the fixed-size scratch arrays of the evaluators.
inline constexpr int kMaxDegree = 15;

/// Checks a clamped knot vector for `count` basis functions of `degree`:
/// 1 <= degree <= kMaxDegree, count >= degree + 1, size == count + degree + 1,
/// finite, non-decreasing, clamped at both ends, a non-empty domain, no
/// interior knot repeated more than `degree` times. The error says which rule
/// and where ("knots[5] = 0.4 is below knots[4] = 0.5"), without a file name.
Status validate_knots(std::span<const double> knots, int degree, int count);

/// Index of the knot span [knots[s], knots[s+1]) holding t (A2.1); t at the
/// domain's end gives the last non-empty span; t outside is clamped.
int find_span(std::span<const double> knots, int degree, int count, double t);

/// The degree + 1 non-zero basis values N[span-degree .. span] at t (A2.2),
/// written to `out` (degree + 1 values).
void basis_functions(std::span<const double> knots, int degree, int span, double t, double* out);

/// Basis values and derivatives up to `order` at t (A2.3): out[k * (degree+1)
/// + j] is the k-th derivative of N[span-degree+j]; (order+1)*(degree+1)
/// values. Derivatives above the degree are zero.
void basis_derivatives(std::span<const double> knots, int degree, int span, double t, int order,
                       double* out);

/// Greville abscissae: g_i = (knots[i+1] + ... + knots[i+degree]) / degree,
/// one per basis function (count values). On a flat surface whose control
/// points sit at their Greville abscissae, S(g_i, g_j) = P_ij is the point
/// P_ij has most influence on (the paper's "parametric image", §4.2), and
/// sum_i g_i N_i(t) = t (linear precision).
std::vector<double> greville_abscissae(std::span<const double> knots, int degree);

/// A clamped knot vector with uniformly spaced interior knots on [lo, hi].
std::vector<double> uniform_clamped_knots(int degree, int count, double lo = 0.0, double hi = 1.0);

/// Distinct knot values with non-empty spans after them: the break points of
/// the domain (first..last, each once).
std::vector<double> breakpoints(std::span<const double> knots, int degree, int count);

}  // namespace sculpt::core::nurbs
