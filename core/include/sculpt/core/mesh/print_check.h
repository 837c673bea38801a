#pragma once
// Will this mesh print? A slicer needs a closed, consistently oriented,
// manifold surface that nowhere passes through itself; a user needs its
// volume and size in millimetres (`sculpt mesh --check`).
//
// Self-intersection: every pair of triangles whose boxes overlap (found
// through a uniform grid of cells about the mean triangle size) and that
// share no vertex is tested edge against triangle (Moller-Trumbore). Pairs
// sharing a vertex are neighbours on the surface and are not tested (a fold
// at a shared vertex is left to the manifold check); coplanar overlaps and
// mere contact (a vertex lying on another triangle) are not counted:
// marching cubes makes neither between non-neighbours.

#include <cstdint>
#include <utility>
#include <vector>

#include "sculpt/core/mesh/mesh.h"

namespace sculpt::core {

struct PrintCheck {
  MeshTopology topology;
  int64_t components = 0;
  /// Pairs of triangles that pass through each other.
  int64_t self_intersections = 0;
  /// Signed volume, mm^3 (positive when the triangles face outward).
  double volume_mm3 = 0.0;
  MeshBounds bounds_mm;

  /// Closed (watertight), one orientation, manifold, and nowhere through itself.
  bool printable() const {
    return topology.manifold() && self_intersections == 0 && topology.faces > 0 && volume_mm3 > 0;
  }
};

/// Checks `mesh` (positions in voxels) with voxels `voxel_mm` wide.
PrintCheck check_print(const Mesh& mesh, double voxel_mm);

/// Pairs of triangles of `mesh` that pass through each other (see above);
/// stops counting at `limit`.
int64_t count_self_intersections(const Mesh& mesh, int64_t limit = INT64_MAX);

/// The same pairs, as triangle indices (i, j), i < j, at most `limit`.
std::vector<std::pair<uint32_t, uint32_t>> self_intersecting_pairs(const Mesh& mesh,
                                                                   int64_t limit = INT64_MAX);

}  // namespace sculpt::core
