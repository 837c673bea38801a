#pragma once
// Smooth normals for a mesh of a volume's iso-surface from the distance
// field's gradient (Jones & Satherley §2, §3.2): the signed distance to the
// sub-voxel surface (the tiling-tetrahedra triangulation of the level
// function) is computed only at the voxels the gradient reads, the 4^3
// stencil around each vertex (central differences at the 8 voxels around it,
// trilinearly interpolated: distance_normals.h). So a brick's mesh costs a
// few thousand nearest-surface queries, not a distance transform of the
// volume.

#include "sculpt/core/mesh/mesh.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::core {

/// Sets mesh.normals (positions in the volume's voxel coordinates) to the
/// unit distance gradient; a vertex where the gradient vanishes keeps its
/// normal. Reads the volume within 4 voxels of the mesh's bounding box.
void set_normals_from_surface_distance(const Volume& volume, Mesh& mesh);

}  // namespace sculpt::core
