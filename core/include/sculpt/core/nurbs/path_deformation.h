#pragma once
// The path constraint of La Greca, Raffin & Gesquière §4.3: the point S(u,v)
// is dragged along a curve C(t), C(0) = S(u,v), in N steps. Step k < N-1
// moves the control points with f(i,j) >= s(k) = k / (N-1) (equation (3),
// the set L_k, which shrinks as k grows) rigidly: rotated by alpha_k, the
// angle between e_k = C((k+1)/N) - C(k/N) and e_(k+1), about the axis through
// C(k/N) along e_k x e_(k+1), then translated by e_k. The last step applies
// equation (2) with the influence f restricted to L_(N-1), so it satisfies
// the constraint S(u,v) = C(1) exactly (up to rounding).
//
// Two ways to drive it:
//  - from a curve (PathDeformation::from_curve): N known in advance
//    (default 10 x degree x control points of C, the paper's choice); call
//    step() until done(), re-drawing with the returned moved points;
//  - live from device points (PathDeformation::live): push_point() for each
//    new position of the dragged point; segment k is applied when point k+2
//    arrives (its rotation needs the next segment); finish() applies the
//    rest and the exact last step. `expected_steps` plays the role of N for
//    the thresholds.
//
// Threshold detail: with f normalised to max 1, s(N-1) = 1 keeps only the
// control points of maximal influence; if none of those acts on S(u,v), the
// last threshold is lowered to the largest f among the control points that
// do, so equation (2) is always solvable. Control points with f = 0 never
// move (bit-identical).

#include <optional>
#include <span>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "sculpt/base/result.h"
#include "sculpt/core/nurbs/nurbs_curve.h"
#include "sculpt/core/nurbs/nurbs_surface.h"
#include "sculpt/core/nurbs/rigid_motion.h"

namespace sculpt::core::nurbs {

struct PathOptions {
  /// Number of steps N; 0 means 10 x degree x control points of the curve.
  int steps = 0;
  /// Apply the rotations alpha_k (off: translations only).
  bool rotate = true;
  /// How far C(0) may lie from S(u,v), relative to the size of the surface's
  /// control net (its bounding-box diagonal).
  double start_tolerance = 1e-6;
};

/// What one step did.
struct PathStep {
  int step = 0;            ///< k
  double threshold = 0.0;  ///< s(k)
  double angle_rad = 0.0;  ///< alpha_k (0 on the last step)
  std::vector<int> moved;  ///< indices of the control points that moved, increasing
  /// Steps k < N-1 move every point of `moved` by this one rigid motion
  /// (SurfaceTessellator::update uses it); empty for the last step.
  std::optional<RigidMotion> motion;
};

/// Rotation by `angle_rad` about the unit `axis` (right-handed; Rodrigues).
glm::dmat3 rotation_about_axis(glm::dvec3 axis, double angle_rad);
/// The rotation taking the direction of `from` to that of `to` about
/// from x to (identity when they are parallel or either is zero); its angle
/// in `angle_rad` if given.
glm::dmat3 rotation_between(glm::dvec3 from, glm::dvec3 to, double* angle_rad = nullptr);

class PathDeformation {
 public:
  /// Checks the curve (validate), the influence (one value >= 0 per control
  /// point, some control point with f > 0 acting on S(u,v)), (u, v) inside the
  /// domain, and that C(0) is S(u,v) within the tolerance; the error says
  /// which. The surface is copied and deformed inside.
  static Result<PathDeformation> from_curve(NurbsSurface surface, double u, double v,
                                            std::vector<double> influence, const NurbsCurve& path,
                                            const PathOptions& options = {});
  /// Live mode: the path is given point by point, starting at S(u,v).
  static Result<PathDeformation> live(NurbsSurface surface, double u, double v,
                                      std::vector<double> influence, int expected_steps,
                                      bool rotate = true);

  /// Number of steps N (live mode: the expected count).
  int step_count() const { return steps_; }
  int steps_done() const { return done_steps_; }
  bool done() const { return finished_; }

  /// Curve mode: applies the next step. Must not be called when done().
  PathStep step();
  /// Curve mode: applies all remaining steps; returns every control point
  /// that moved at least once (increasing).
  std::vector<int> run();

  /// Live mode: the dragged point's new position. Returns the step applied
  /// (none for the first point after the start).
  std::optional<PathStep> push_point(glm::dvec3 point);
  /// Live mode: applies the pending segment and the exact last step to the
  /// last pushed point (or `target` if given). Returns the steps applied.
  std::vector<PathStep> finish(std::optional<glm::dvec3> target = std::nullopt);

  const NurbsSurface& surface() const { return surface_; }
  double u() const { return u_; }
  double v() const { return v_; }
  /// Where S(u,v) should be now: C(k/N) after k steps (curve mode), the
  /// last applied path point (live mode).
  glm::dvec3 expected_point() const { return expected_; }
  /// |S(u,v) - expected_point()|.
  double residual() const;
  /// The normalised influence f (max 1).
  const std::vector<double>& influence() const { return f_; }

 private:
  PathDeformation() = default;
  // Rotates L about `pivot` by `rot` and translates it by e (steps k < N-1).
  PathStep rigid_step(int k, glm::dvec3 e, std::optional<glm::dvec3> next, glm::dvec3 pivot);
  PathStep final_step(int k, glm::dvec3 target);
  double threshold(int k) const;

  NurbsSurface surface_;
  double u_ = 0.0, v_ = 0.0;
  std::vector<double> f_;
  std::optional<NurbsCurve> path_;
  int steps_ = 1;
  int done_steps_ = 0;
  bool finished_ = false;
  bool rotate_ = true;
  glm::dvec3 expected_{0.0};
  // Live mode: the last applied point and the segment waiting for its successor.
  std::vector<glm::dvec3> pending_;
};

}  // namespace sculpt::core::nurbs
