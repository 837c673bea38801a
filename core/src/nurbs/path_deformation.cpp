// Path constraint (La Greca, Raffin & Gesquière §4.3, equation (3)).
//
// Why the shrinking sets: with one fixed localisation every step would add up
// to the straight constraint e = C(1) - C(0) (the segments sum to it), so the
// surface would not follow the curve; thresholding f by s(k) = k/(N-1) lets
// the outer control points stop early while the ones near (u,v) travel the
// whole path, which "spreads the surface along the curved path".

#include "sculpt/core/nurbs/path_deformation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "sculpt/core/nurbs/influence.h"
#include "sculpt/core/nurbs/punctual_constraint.h"

namespace sculpt::core::nurbs {
namespace {

std::string vec(glm::dvec3 p) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.9g, %.9g, %.9g)", p.x, p.y, p.z);
  return text;
}

Status check_common(const NurbsSurface& s, double u, double v, std::vector<double>& f) {
  if (!(u >= s.u_min() && u <= s.u_max() && v >= s.v_min() && v <= s.v_max())) {
    return Error("(u, v) = (" + std::to_string(u) + ", " + std::to_string(v) +
                 ") is outside the surface's domain");
  }
  if (f.size() != static_cast<size_t>(s.point_count())) {
    return Error("influence has " + std::to_string(f.size()) + " values for " +
                 std::to_string(s.point_count()) + " control points");
  }
  double top = 0.0;
  for (double x : f) {
    if (!(x >= 0.0) || !std::isfinite(x)) return Error("influence values must be finite and >= 0");
    top = std::max(top, x);
  }
  if (!(top > 0.0) || !(influence_at(s, u, v, f) > 0.0)) {
    return Error("no control point with a non-zero influence acts on S(u, v)");
  }
  for (double& x : f)
    x /= top;
  return {};
}

}  // namespace

glm::dmat3 rotation_about_axis(glm::dvec3 axis, double angle) {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  const double t = 1.0 - c;
  const double x = axis.x, y = axis.y, z = axis.z;
  // Column-major (glm): m[col][row].
  return glm::dmat3(t * x * x + c, t * x * y + s * z, t * x * z - s * y,  //
                    t * x * y - s * z, t * y * y + c, t * y * z + s * x,  //
                    t * x * z + s * y, t * y * z - s * x, t * z * z + c);
}

glm::dmat3 rotation_between(glm::dvec3 from, glm::dvec3 to, double* angle_rad) {
  const glm::dvec3 axis = glm::cross(from, to);
  const double sine = glm::length(axis);
  const double cosine = glm::dot(from, to);
  const double angle = std::atan2(sine, cosine);
  if (angle_rad != nullptr) *angle_rad = 0.0;
  // Parallel (or zero) segments: no turn. Antiparallel ones have no
  // defined axis either; a device reversing its motion is not a turn.
  if (!(sine > 1e-12 * glm::length(from) * glm::length(to)) || sine == 0.0) return glm::dmat3(1.0);
  if (angle_rad != nullptr) *angle_rad = angle;
  return rotation_about_axis(axis / sine, angle);
}

Result<PathDeformation> PathDeformation::from_curve(NurbsSurface surface, double u, double v,
                                                    std::vector<double> influence,
                                                    const NurbsCurve& path,
                                                    const PathOptions& options) {
  if (Status st = validate(path); !st) return Error("path: " + st.error().message());
  if (Status st = check_common(surface, u, v, influence); !st) return st.error();
  const glm::dvec3 start = evaluate(surface, u, v);
  const glm::dvec3 c0 = evaluate(path, path.domain_min());
  glm::dvec3 lo = surface.points.front();
  glm::dvec3 hi = lo;
  for (const glm::dvec3& p : surface.points) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const double tolerance = options.start_tolerance * std::max(glm::length(hi - lo), 1e-300);
  if (glm::length(c0 - start) > tolerance) {
    return Error("path: starts at " + vec(c0) + " but S(u, v) is " + vec(start) + ", " +
                 std::to_string(glm::length(c0 - start)) + " away (C(0) must be S(u, v))");
  }
  if (options.steps < 0) return Error("steps must be positive");
  PathDeformation d;
  d.surface_ = std::move(surface);
  d.u_ = u;
  d.v_ = v;
  d.f_ = std::move(influence);
  d.path_ = path;
  d.steps_ = options.steps > 0 ? options.steps : 10 * path.degree * path.count();
  d.rotate_ = options.rotate;
  d.expected_ = start;
  return d;
}

Result<PathDeformation> PathDeformation::live(NurbsSurface surface, double u, double v,
                                              std::vector<double> influence, int expected_steps,
                                              bool rotate) {
  if (Status st = check_common(surface, u, v, influence); !st) return st.error();
  if (expected_steps < 2) return Error("expected_steps must be at least 2");
  PathDeformation d;
  d.expected_ = evaluate(surface, u, v);
  d.surface_ = std::move(surface);
  d.u_ = u;
  d.v_ = v;
  d.f_ = std::move(influence);
  d.steps_ = expected_steps;
  d.rotate_ = rotate;
  return d;
}

double PathDeformation::threshold(int k) const {
  if (steps_ <= 1) return 1.0;
  // Live paths may run longer than expected: hold the last rigid threshold.
  return static_cast<double>(std::min(k, steps_ - 2)) / (steps_ - 1);
}

PathStep PathDeformation::rigid_step(int k, glm::dvec3 e, std::optional<glm::dvec3> next,
                                     glm::dvec3 pivot) {
  PathStep r;
  r.step = k;
  r.threshold = threshold(k);
  glm::dmat3 rot(1.0);
  if (rotate_ && next) rot = rotation_between(e, *next, &r.angle_rad);
  const bool turn = r.angle_rad != 0.0;
  for (int i = 0; i < surface_.point_count(); ++i) {
    const double f = f_[static_cast<size_t>(i)];
    if (!(f > 0.0) || f < r.threshold) continue;
    glm::dvec3& p = surface_.points[static_cast<size_t>(i)];
    if (turn) p = pivot + rot * (p - pivot);
    p += e;
    r.moved.push_back(i);
  }
  r.motion = RigidMotion{turn ? rot : glm::dmat3(1.0), pivot, e};
  ++done_steps_;
  return r;
}

PathStep PathDeformation::final_step(int k, glm::dvec3 target) {
  // L_(N-1): f >= 1, lowered to the largest influence acting on S(u,v).
  const RationalBasis r = rational_basis(surface_, u_, v_);
  double top = 0.0;
  for (int b = 0; b < r.width_v; ++b) {
    for (int a = 0; a < r.width_u; ++a) {
      if (r.values[static_cast<size_t>(a + r.width_u * b)] > 0.0) {
        top = std::max(top, f_[static_cast<size_t>(surface_.index(r.first_i + a, r.first_j + b))]);
      }
    }
  }
  const double s = std::min(1.0, top);
  std::vector<double> last(f_.size(), 0.0);
  for (size_t i = 0; i < f_.size(); ++i)
    last[i] = f_[i] >= s ? f_[i] : 0.0;
  PathStep step;
  step.step = k;
  step.threshold = s;
  Result<std::vector<int>> moved = apply_linear_constraint(surface_, u_, v_, target, last);
  // check_common guaranteed an acting control point with the largest f.
  if (moved.ok()) step.moved = std::move(moved.value());
  expected_ = target;
  ++done_steps_;
  finished_ = true;
  return step;
}

PathStep PathDeformation::step() {
  const int k = done_steps_;
  const int n = steps_;
  const NurbsCurve& c = *path_;
  auto at = [&](int i) {
    return evaluate(c, c.domain_min() + (c.domain_max() - c.domain_min()) * i / n);
  };
  if (k + 1 >= n) return final_step(k, at(n));
  const glm::dvec3 ck = at(k);
  const glm::dvec3 ck1 = at(k + 1);
  PathStep r = rigid_step(k, ck1 - ck, at(k + 2) - ck1, ck);
  expected_ = ck1;
  return r;
}

std::vector<int> PathDeformation::run() {
  std::set<int> all;
  while (!done()) {
    const PathStep s = step();
    all.insert(s.moved.begin(), s.moved.end());
  }
  return {all.begin(), all.end()};
}

std::optional<PathStep> PathDeformation::push_point(glm::dvec3 point) {
  pending_.push_back(point);
  if (pending_.size() < 2) return std::nullopt;
  const glm::dvec3 e = pending_[0] - expected_;
  const glm::dvec3 next = pending_[1] - pending_[0];
  PathStep r = rigid_step(done_steps_, e, next, expected_);
  expected_ = pending_[0];
  pending_.erase(pending_.begin());
  return r;
}

std::vector<PathStep> PathDeformation::finish(std::optional<glm::dvec3> target) {
  std::vector<PathStep> steps;
  if (target) {
    if (std::optional<PathStep> s = push_point(*target)) steps.push_back(std::move(*s));
  }
  const glm::dvec3 goal = pending_.empty() ? expected_ : pending_.back();
  pending_.clear();
  steps.push_back(final_step(done_steps_, goal));
  return steps;
}

double PathDeformation::residual() const {
  return glm::length(evaluate(surface_, u_, v_) - expected_);
}

}  // namespace sculpt::core::nurbs
