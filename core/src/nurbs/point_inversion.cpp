// Newton point inversion (The NURBS Book §6.1, equations 6.3-6.8). A grid of
// seeds over every knot span avoids the far local minima a single seed falls
// into on a waved sheet.

#include "sculpt/core/nurbs/point_inversion.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

namespace sculpt::core::nurbs {
namespace {

std::vector<double> seed_parameters(const std::vector<double>& knots, int degree, int count,
                                    int per_span) {
  const std::vector<double> b = breakpoints(knots, degree, count);
  std::vector<double> t;
  for (size_t i = 0; i + 1 < b.size(); ++i) {
    for (int k = 0; k < per_span; ++k)
      t.push_back(b[i] + (b[i + 1] - b[i]) * k / per_span);
  }
  t.push_back(b.back());
  return t;
}

struct Seed {
  double d2;
  double u;
  double v;
};

}  // namespace

SurfacePoint closest_point(const NurbsSurface& s, glm::dvec3 query, const InversionOptions& o) {
  const int per_span = std::max(1, o.samples_per_span);
  const std::vector<double> us = seed_parameters(s.knots_u, s.degree_u, s.count_u, per_span);
  const std::vector<double> vs = seed_parameters(s.knots_v, s.degree_v, s.count_v, per_span);
  std::vector<Seed> seeds;
  seeds.reserve(us.size() * vs.size());
  for (double v : vs) {
    for (double u : us) {
      const glm::dvec3 d = evaluate(s, u, v) - query;
      seeds.push_back({glm::dot(d, d), u, v});
    }
  }
  const size_t keep = std::min(seeds.size(), static_cast<size_t>(std::max(1, o.seeds)));
  std::partial_sort(seeds.begin(), seeds.begin() + static_cast<ptrdiff_t>(keep), seeds.end(),
                    [](const Seed& a, const Seed& b) { return a.d2 < b.d2; });
  const double du = s.u_max() - s.u_min();
  const double dv = s.v_max() - s.v_min();
  SurfacePoint best;
  best.distance = INFINITY;
  for (size_t k = 0; k < keep; ++k) {
    double u = seeds[k].u;
    double v = seeds[k].v;
    for (int it = 0; it < o.max_iterations; ++it) {
      const SurfaceDerivatives d = derivatives(s, u, v, 2);
      const glm::dvec3 r = d.s - query;
      const double f = glm::dot(r, d.su);
      const double g = glm::dot(r, d.sv);
      const double a = glm::dot(d.su, d.su) + glm::dot(r, d.suu);
      const double b = glm::dot(d.su, d.sv) + glm::dot(r, d.suv);
      const double c = glm::dot(d.sv, d.sv) + glm::dot(r, d.svv);
      const double det = a * c - b * b;
      if (!(std::abs(det) > 0.0)) break;
      const double step_u = -(c * f - b * g) / det;
      const double step_v = -(a * g - b * f) / det;
      const double nu = std::clamp(u + step_u, s.u_min(), s.u_max());
      const double nv = std::clamp(v + step_v, s.v_min(), s.v_max());
      const double moved = std::abs(nu - u) / du + std::abs(nv - v) / dv;
      u = nu;
      v = nv;
      if (moved < o.parameter_tolerance) break;
    }
    const glm::dvec3 p = evaluate(s, u, v);
    const double dist = glm::length(p - query);
    // Newton can climb away from a seed on a saddle; the seed itself is a
    // valid answer then.
    const double seed_dist = std::sqrt(seeds[k].d2);
    if (seed_dist < dist && seed_dist < best.distance) {
      best = {seeds[k].u, seeds[k].v, evaluate(s, seeds[k].u, seeds[k].v), seed_dist};
    } else if (dist < best.distance) {
      best = {u, v, p, dist};
    }
  }
  return best;
}

CurvePoint closest_point(const NurbsCurve& c, glm::dvec3 query, const InversionOptions& o) {
  const int per_span = std::max(1, o.samples_per_span) * 4;
  const std::vector<double> ts = seed_parameters(c.knots, c.degree, c.count(), per_span);
  std::vector<std::pair<double, double>> seeds;
  for (double t : ts) {
    const glm::dvec3 d = evaluate(c, t) - query;
    seeds.emplace_back(glm::dot(d, d), t);
  }
  const size_t keep = std::min(seeds.size(), static_cast<size_t>(std::max(1, o.seeds)));
  std::partial_sort(seeds.begin(), seeds.begin() + static_cast<ptrdiff_t>(keep), seeds.end());
  const double span = c.domain_max() - c.domain_min();
  CurvePoint best;
  best.distance = INFINITY;
  for (size_t k = 0; k < keep; ++k) {
    double t = seeds[k].second;
    for (int it = 0; it < o.max_iterations; ++it) {
      const std::vector<glm::dvec3> d = derivatives(c, t, 2);
      const glm::dvec3 r = d[0] - query;
      const double f = glm::dot(r, d[1]);
      const double df = glm::dot(r, d[2]) + glm::dot(d[1], d[1]);
      if (!(std::abs(df) > 0.0)) break;
      const double nt = std::clamp(t - f / df, c.domain_min(), c.domain_max());
      const double moved = std::abs(nt - t) / span;
      t = nt;
      if (moved < o.parameter_tolerance) break;
    }
    const glm::dvec3 p = evaluate(c, t);
    const double dist = glm::length(p - query);
    const double seed_dist = std::sqrt(seeds[k].first);
    if (seed_dist < dist && seed_dist < best.distance) {
      best = {seeds[k].second, evaluate(c, seeds[k].second), seed_dist};
    } else if (dist < best.distance) {
      best = {t, p, dist};
    }
  }
  return best;
}

}  // namespace sculpt::core::nurbs
