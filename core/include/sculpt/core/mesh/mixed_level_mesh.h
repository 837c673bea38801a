#pragma once
// One surface from bricks meshed at different levels of detail, without
// cracks (DESIGN.md §4 "Mixed levels must not show cracks").
//
// The method (a documented alternative to Transvoxel's transition cells):
//  1. Every brick marches its own box [b e, (b+1) e] on its level's grid;
//     level-k point i sits at i 2^k, so all levels' grid planes meet on the
//     brick faces.
//  2. Samples on a brick face, edge or corner are taken from the coarsest
//     level among the bricks sharing it, interpolated (bilinearly on a face,
//     linearly along an edge) to the finer grids. Both sides of a face then
//     cross every coarse grid line at the same point, and each such vertex is
//     welded by the key of the coarse edge it lies on.
//  3. Between those shared vertices the finer brick's boundary is a polyline
//     where the coarser brick's is one segment; the thin planar gaps they
//     leave in the face plane are closed by fanning each boundary loop of
//     the welded mesh ("stitching").
// The result is closed (every edge in exactly two triangles, consistently
// oriented) for closed shapes that stay clear of the volume's low faces by
// one coarse voxel (the whole-level meshes of marching_cubes.h have no such
// limit). Known limit: where many bricks of different levels meet around a
// brick edge, the stitch can join gaps into a small handle or pinch a vertex
// (about one in five random level assignments in the tests changes the Euler
// characteristic; level maps where neighbours differ along faces only, as a
// view-distance LOD gives, keep it).

#include <cstdint>
#include <span>

#include "sculpt/core/mesh/marching_cubes.h"
#include "sculpt/core/mesh/mesh.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::core {

struct MixedLevelStats {
  int64_t stitch_loops = 0;      ///< gaps closed in brick faces
  int64_t stitch_triangles = 0;  ///< triangles added for them
  int64_t stitch_off_face = 0;   ///< loop vertices not on a brick face (0 unless broken)
};

/// The surface of `volume` with brick b at level brick_levels[i], i the brick
/// index ((b.z * grid.y + b.y) * grid.x + b.x), each in [0, volume.levels()].
Mesh mixed_level_mesh(const Volume& volume, std::span<const int> brick_levels,
                      const MarchingCubesOptions& options = {}, MixedLevelStats* stats = nullptr);

}  // namespace sculpt::core
