#pragma once
// Internal to the mesh module: closing the gaps a finer mesh leaves against
// a coarser one across the faces of its box (mixed_level_mesh.h, step 3),
// for a brick among bricks of other levels and for the parts of a brick's
// interim mesh (mixed_level_mesh.cpp, interim_mesh.cpp).

#include <functional>

#include <glm/vec3.hpp>

#include "sculpt/core/mesh/mesh.h"
#include "sculpt/core/mesh/mixed_level_mesh.h"

namespace sculpt::core::detail {

/// `mesh` covers the box [lo, hi] (level-0 voxels) and was marched finer
/// than some of what lies across its faces, its samples there interpolated
/// from the coarser grid. Inside each square of that grid it meets the face
/// along a polyline from one crossing to the other where the coarser side
/// meets it along one segment; each such gap is fanned from the polyline's
/// centroid, closed by the chord between its ends, so every edge ends up in
/// two triangles. `coarser_faces` (bit 2 axis + 1 for the high side) are the faces
/// with anything coarser across; coarser_across(face, mid) is the level
/// across face `face` at level-0 point `mid` (a gap edge's midpoint), or -1
/// where the side across is not coarser.
void stitch_gaps(glm::vec3 lo, glm::vec3 hi, unsigned coarser_faces,
                 const std::function<int(int face, glm::dvec3 mid)>& coarser_across, Mesh& mesh,
                 MixedLevelStats& st);

}  // namespace sculpt::core::detail
