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
// The basis functions of every sample are computed once (again only when
// the knots change); after control points move, update() visits only the
// patches whose support holds a moved point (a control point (i, j)
// influences the knot spans i..i+p along u and j..j+q along v), and
// evaluates their vertices exactly as a rebuild does (bit-identical). When all moved points
// underwent one rigid motion (a path step), a vertex whose whole support moved is moved by that
// motion instead of being re-evaluated (S = sum R_ij P_ij with sum R_ij = 1 commutes with rigid
// motions; the normal turns with the rotation); only the vertices on the rim of the moved set are
// evaluated. Positions and normals are kept in double precision inside, so repeated motions do not
// drift.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec4.hpp>

#include "sculpt/core/mesh/mesh.h"
#include "sculpt/core/nurbs/nurbs_surface.h"
#include "sculpt/core/nurbs/rigid_motion.h"

namespace sculpt::core::nurbs {

class SurfaceTessellator {
 public:
  /// Tessellates `surface` (which must pass validate()) with
  /// `samples_per_span` >= 1 cells per knot span and direction.
  SurfaceTessellator(const NurbsSurface& surface, int samples_per_span);
  /// Tessellates with about `cells_u` x `cells_v` cells over the whole
  /// domain: each knot span gets max(1, round(cells * span length / domain
  /// length)) cells. Refining the surface (which only splits spans) then
  /// keeps the mesh about the same size, which is what the station wants
  /// when the path constraint refines the sheet.
  static SurfaceTessellator with_cells(const NurbsSurface& surface, int cells_u, int cells_v);

  /// Brings the mesh up to date after the control points `moved` (indices
  /// i + count_u * j) of `surface` changed; if `motion` is given, they all
  /// moved by it (PathStep::motion). If the surface's knots or counts
  /// changed (refinement), everything is rebuilt. Returns the number of
  /// patches whose vertices changed.
  int update(const NurbsSurface& surface, std::span<const int> moved,
             const RigidMotion* motion = nullptr);
  /// Rebuilds everything from `surface`.
  void rebuild(const NurbsSurface& surface);

  const Mesh& mesh() const { return mesh_; }
  int patches_u() const { return static_cast<int>(spans_u_.size()); }
  int patches_v() const { return static_cast<int>(spans_v_.size()); }
  int patch_count() const { return patches_u() * patches_v(); }
  /// Cells per knot span (0 when built with_cells()).
  int samples_per_span() const { return per_span_; }
  /// Vertices per row (along u) and rows.
  int vertices_u() const { return static_cast<int>(axis_u_.size()); }
  int vertices_v() const { return static_cast<int>(axis_v_.size()); }
  /// Parameters (u, v) of vertex (a, b) (vertex index a + vertices_u() * b).
  double vertex_u(int a) const { return axis_u_[static_cast<size_t>(a)].t; }
  double vertex_v(int b) const { return axis_v_[static_cast<size_t>(b)].t; }
  /// Vertices evaluated from the basis (rebuilds included) and vertices
  /// moved rigidly, over all calls so far.
  int64_t vertices_evaluated() const { return vertices_evaluated_; }
  int64_t vertices_moved_rigidly() const { return vertices_moved_rigidly_; }

 private:
  SurfaceTessellator() = default;
  // One sample along an axis: its parameter, knot span, and the degree+1
  // basis values and first derivatives there.
  struct AxisSample {
    double t = 0.0;
    int span = 0;
    std::array<double, kMaxDegree + 1> n{};
    std::array<double, kMaxDegree + 1> dn{};
  };
  void build_axis(const std::vector<double>& knots, int degree, int count, int cells,
                  std::vector<AxisSample>& axis, std::vector<int>& spans, std::vector<int>& first);
  // Vertex row b: the control net contracted along v with that row's basis
  // values and derivatives, for control columns [first, last] (row_q_,
  // row_dq_); then each vertex of the row is a sum of degree_u + 1 terms.
  void prepare_row(int b, int first, int last);
  void contract_column(int b, int i);
  // The same contraction for the columns [first, last] of vertex row b that
  // this row has not contracted yet (column_stamp_ != row_stamp_); update()
  // bumps row_stamp_ per row, so a rim vertex costs only its own columns.
  void prepare_columns(int b, int first, int last);
  void evaluate_vertex(int a, int b);
  // Moved control points in the support of knot span (su, sv), from the
  // prefix sums of the moved flags.
  int moved_in_support(int su, int sv) const;

  int per_span_ = 0;
  int cells_u_ = 0, cells_v_ = 0;  // with_cells() targets, 0 = per_span_ cells per span
  int degree_u_ = 0, degree_v_ = 0, count_u_ = 0, count_v_ = 0;
  std::vector<double> knots_u_, knots_v_;
  std::vector<glm::dvec4> pw_;  // homogeneous control points, u fastest
  std::vector<AxisSample> axis_u_, axis_v_;
  std::vector<int> spans_u_, spans_v_;  // knot-span index of each patch column / row
  // First vertex of each patch column / row, plus the vertex count: the
  // vertices of patch column p are [first_u_[p], first_u_[p + 1]).
  std::vector<int> first_u_, first_v_;
  std::vector<glm::dvec4> row_q_, row_dq_;  // count_u values, see prepare_row
  std::vector<int> moved_sum_;              // (count_u+1) x (count_v+1) prefix sums of moved flags
  // Scratch kept between update() calls so a step allocates nothing.
  std::vector<uint8_t> moved_flag_;  // count_u x count_v, all 0 between calls
  std::vector<int> patch_moved_;     // per patch column of one patch row
  std::vector<uint32_t> column_stamp_;
  uint32_t row_stamp_ = 0;
  std::vector<glm::dvec3> positions_, normals_;  // double copies of the mesh's
  Mesh mesh_;
  int64_t vertices_evaluated_ = 0;
  int64_t vertices_moved_rigidly_ = 0;
};

/// One-shot tessellation (see SurfaceTessellator).
Mesh tessellate(const NurbsSurface& surface, int samples_per_span = 8);

}  // namespace sculpt::core::nurbs
