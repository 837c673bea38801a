#pragma once
// Point inversion: the parameters of the point of a NURBS surface or curve
// closest to a 3D point (The NURBS Book §6.1): Newton iterations on
// (S - P) . Su = 0, (S - P) . Sv = 0, seeded from the best samples of a
// grid over every knot span, clamped to the domain. The station uses it to
// pick the point under the device's tool tip.

#include <glm/vec3.hpp>

#include "sculpt/core/nurbs/nurbs_curve.h"
#include "sculpt/core/nurbs/nurbs_surface.h"

namespace sculpt::core::nurbs {

struct InversionOptions {
  /// Seed samples per knot span and direction.
  int samples_per_span = 4;
  /// Newton runs from this many of the closest seeds; the best result wins.
  int seeds = 4;
  int max_iterations = 30;
  /// Stop when a Newton step moves the parameters by less than this
  /// fraction of the domain.
  double parameter_tolerance = 1e-14;
};

struct SurfacePoint {
  double u = 0.0;
  double v = 0.0;
  glm::dvec3 point{0.0};  ///< S(u, v)
  double distance = 0.0;  ///< |S(u, v) - query|, caller's units
};

struct CurvePoint {
  double t = 0.0;
  glm::dvec3 point{0.0};
  double distance = 0.0;
};

/// The closest point of `surface` to `query` (a local minimum of the
/// distance reached from the best seeds; on a surface folding back close to
/// itself another local minimum may win).
SurfacePoint closest_point(const NurbsSurface& surface, glm::dvec3 query,
                           const InversionOptions& options = {});

/// The closest point of `curve` to `query`.
CurvePoint closest_point(const NurbsCurve& curve, glm::dvec3 query,
                         const InversionOptions& options = {});

}  // namespace sculpt::core::nurbs
