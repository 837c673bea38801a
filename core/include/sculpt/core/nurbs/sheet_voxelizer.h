#pragma once
// Voxelising a tessellated NURBS sheet as a shell of given thickness into
// the material (the station's "add or subtract the sheet" action).
//
// The shell is the set of points within thickness / 2 of the triangles
// (the exact point-to-triangle distance of core/distance). Its density
// ramps over two voxels as every shape's does (density_from_distance(d -
// thickness / 2)), so the iso-surface 127.5 lies at distance thickness / 2
// and gradient normals shade it smoothly.
// Only bricks meeting the shell's bounding box are decoded and re-encoded.
// Coordinates are voxel units (voxel (x, y, z) at x, y, z).

#include <glm/vec3.hpp>

#include "sculpt/core/grid/box.h"
#include "sculpt/core/mesh/mesh.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::core::nurbs {

enum class ShellMode {
  kAdd,       ///< material = max(material, shell)
  kSubtract,  ///< material = min(material, 255 - shell)
};

/// Writes the shell of `mesh` (thickness_vox > 0, voxel units) into
/// `volume`. Returns the voxel box that was visited (clipped to the volume;
/// empty if the shell misses it).
Box voxelize_shell(const Mesh& mesh, double thickness_vox, ShellMode mode, Volume& volume);

}  // namespace sculpt::core::nurbs
