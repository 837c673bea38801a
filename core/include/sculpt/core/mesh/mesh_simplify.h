#pragma once
// A lighter mesh to export: the demo's head leaves as 238k triangles (5.9 MB
// of PLY); a game engine, a web viewer or a print service wants a tenth.
// Edges are collapsed by meshoptimizer's quadric-error simplifier (Debian's
// libmeshoptimizer-dev) down to a share of the triangles or within an error
// bound. Simplified whole, the demo's head came back with a few edges in
// four triangles (meshoptimizer 0.18 does not check every collapse against
// pinching two sheets together) at every share tried; so the mesh is cut
// into chunks of about 48 mean edges a side and each is simplified alone by
// the station's brick simplifier (brick_simplify.h), the triangles along the
// cuts held, a chunk that would pinch simplified less: the result is as
// closed and manifold as the input. A second pass with the cuts moved by
// half a chunk simplifies what the first held. A share is reached by
// bisecting the error bound. The error is measured, not estimated: the
// two-sided distance between the surfaces at every vertex of each
// (hausdorff_distance); a result beyond the bound is made again with less.
// Where two sheets of the input lie within the error of each other (a coil
// lying on the clay), collapses on both may make them pass through each
// other: a result that does where the input did not is made again with the
// input held as it is around the crossings (count_self_intersections), so
// a marched sculpture's simplified mesh passes the print check too.

#include <cstdint>

#include "sculpt/core/mesh/mesh.h"

namespace sculpt::core {

struct MeshSimplifyOptions {
  /// Keep at most this share of the triangles, (0, 1]; 1: no count target.
  /// Without `max_error`, the surface moves at most two mean edges for it:
  /// a share beyond that comes back as near as it allows.
  double ratio = 1.0;
  /// Move the surface by at most this much (the positions' units); 0: no
  /// error bound (then `ratio` alone decides).
  float max_error = 0.0f;
};

struct SimplifiedMesh {
  Mesh mesh;
  /// The measured two-sided distance between input and result.
  double hausdorff = 0.0;
  /// Passes refused: the surface moved farther than the error bound
  /// (measured), or it still passed through itself after the rounds of
  /// holding; each is followed by one with less.
  int refused_attempts = 0;
  /// Places (boxes around a crossing triangle) where the input was held as
  /// it is because simplifying them made the surface pass through itself.
  int held_places = 0;
};

/// `mesh` simplified (normals follow their vertices). With neither a ratio
/// below 1 nor an error bound, or when four passes could not keep within the
/// bound, the mesh comes back as it was. With both, the share is reached
/// within the bound, or as near as the bound allows.
SimplifiedMesh simplify_mesh(const Mesh& mesh, const MeshSimplifyOptions& options);

/// The larger of: the farthest vertex of `a` from the surface of `b`, and
/// the farthest vertex of `b` from the surface of `a` (exact point-to-
/// triangle distances through a grid of triangles). Vertex-sampled: the
/// true Hausdorff distance can exceed it inside triangles, by at most the
/// surfaces' deviation across one triangle.
double hausdorff_distance(const Mesh& a, const Mesh& b);

}  // namespace sculpt::core
