#pragma once
// Tessellation of a NURBS surface into a core::Mesh with exact normals, and
// re-tessellation of only the patches a deformation step touched.
//
// Every non-empty knot-span rectangle (a "patch") is sampled on a regular
// samples_per_span x samples_per_span grid; patches share their border
// vertices, so the mesh is one watertight sheet of
// (spans_u * k + 1) x (spans_v * k + 1) vertices, u fastest, two triangles
// per cell, counter-clockwise seen from the side Su x Sv points to. Normals
// are unit Su x Sv. Positions are in the surface's units (the station's are
// voxel units), converted to float.
//
// The basis functions of every sample are computed once; after control
// points move, update() re-evaluates only the vertices of patches whose
// basis reaches a moved point: a control point (i, j) influences the knot
// spans i..i+p along u and j..j+q along v.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec4.hpp>

#include "sculpt/core/mesh/mesh.h"
#include "sculpt/core/nurbs/nurbs_surface.h"

namespace sculpt::core::nurbs {

class SurfaceTessellator {
 public:
  /// Tessellates `surface` (which must pass validate()) with
  /// `samples_per_span` >= 1 cells per knot span and direction.
  SurfaceTessellator(const NurbsSurface& surface, int samples_per_span);

  /// Re-evaluates the patches reached by the control points `moved`
  /// (indices i + count_u * j) of `surface`. If the surface's knots or
  /// counts changed (refinement), everything is rebuilt. Returns the number
  /// of patches re-tessellated.
  int update(const NurbsSurface& surface, std::span<const int> moved);
  /// Rebuilds everything from `surface`.
  void rebuild(const NurbsSurface& surface);

  const Mesh& mesh() const { return mesh_; }
  int patches_u() const { return static_cast<int>(spans_u_.size()); }
  int patches_v() const { return static_cast<int>(spans_v_.size()); }
  int patch_count() const { return patches_u() * patches_v(); }
  int samples_per_span() const { return per_span_; }
  /// Vertices per row (along u) and rows.
  int vertices_u() const { return static_cast<int>(axis_u_.size()); }
  int vertices_v() const { return static_cast<int>(axis_v_.size()); }
  /// Parameters (u, v) of vertex (a, b) (vertex index a + vertices_u() * b).
  double vertex_u(int a) const { return axis_u_[static_cast<size_t>(a)].t; }
  double vertex_v(int b) const { return axis_v_[static_cast<size_t>(b)].t; }
  /// Patches re-tessellated by all update() calls so far (rebuilds count all).
  int64_t patches_evaluated() const { return patches_evaluated_; }

 private:
  // One sample along an axis: its parameter, knot span, and the degree+1
  // basis values and first derivatives there.
  struct AxisSample {
    double t = 0.0;
    int span = 0;
    std::vector<double> n;
    std::vector<double> dn;
  };
  void build_axis(const std::vector<double>& knots, int degree, int count,
                  std::vector<AxisSample>& axis, std::vector<int>& spans);
  void evaluate_vertex(int a, int b);
  void evaluate_patch(int pu, int pv);

  int per_span_;
  int degree_u_ = 0, degree_v_ = 0, count_u_ = 0, count_v_ = 0;
  std::vector<double> knots_u_, knots_v_;
  std::vector<glm::dvec4> pw_;  // homogeneous control points, u fastest
  std::vector<AxisSample> axis_u_, axis_v_;
  std::vector<int> spans_u_, spans_v_;  // knot-span index of each patch column / row
  std::vector<uint8_t> dirty_;
  Mesh mesh_;
  int64_t patches_evaluated_ = 0;
};

/// One-shot tessellation (see SurfaceTessellator).
Mesh tessellate(const NurbsSurface& surface, int samples_per_span = 8);

}  // namespace sculpt::core::nurbs
