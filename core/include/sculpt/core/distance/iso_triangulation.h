#pragma once
// The sub-voxel surface of a sampled field (Jones & Satherley §3.2): the zero
// level of a level function phi (negative inside), triangulated per cell with
// tiling tetrahedra so that no cell is ambiguous.
//
// A cell is the cube of 8 voxels with lower corner c; it is transverse when
// its corners are not all on one side. Each cell is split into the 6
// tetrahedra around its main diagonal c -> c + (1,1,1) (Kuhn's split): the
// split of every face is the same seen from both cells, so the triangles of
// neighbouring cells meet edge to edge. phi is linear along each tetrahedron
// edge, so a crossing sits where the linear interpolation is zero.
// Coordinates are voxel units (voxel (x, y, z) at x, y, z).

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/core/grid/dense_grid.h"

namespace sculpt::core {

/// Density threshold of the project: inside means density above 127.5.
inline constexpr float kInsideDensity = 127.5f;

/// Level function of a uint8 density: phi = 127.5 - density (density units),
/// negative inside. Same dims.
DenseGrid<float> level_function(const DenseGrid<uint8_t>& density);

/// Inside mask of a level function: 1 where phi < 0.
DenseGrid<uint8_t> inside_mask(const DenseGrid<float>& phi);

struct Triangle3 {
  glm::vec3 a{0.0f}, b{0.0f}, c{0.0f};
};

/// Most triangles one cell can produce (6 tetrahedra, 2 each).
inline constexpr int kMaxCellTriangles = 12;

/// Triangles of cell `cell` (lower corner; 0 <= cell < dims - 1 on each axis)
/// into `out`; returns how many (0 when the cell is not transverse).
int cell_triangles(const DenseGrid<float>& phi, glm::ivec3 cell,
                   std::array<Triangle3, kMaxCellTriangles>& out);

/// Whether cell `cell` is transverse (corners on both sides of the level).
bool cell_is_transverse(const DenseGrid<float>& phi, glm::ivec3 cell);

/// Every triangle of the zero level, cell by cell (z, y, x order).
std::vector<Triangle3> triangulate_iso_surface(const DenseGrid<float>& phi);

}  // namespace sculpt::core
