#pragma once
// Contour connection through distance fields (Jones & Satherley §4.1, after
// Jones & Chen 1994): a stack of closed 2D contours becomes a closed surface
// without any point correspondence, so one-to-many and many-to-many
// branching need no special case.
//
// Text format (one record a line, '#' starts a comment):
//   sculpt-contours 1            first line, the format and its version
//   dims NX NY NZ                the output grid, voxels
//   contour Z                    a closed polygon in slice z = Z (integer)
//   X Y                          its vertices in voxel units, at least 3,
//                                inside the slice (0..NX-1, 0..NY-1);
//   ...                          the last joins the first
//   end                          closes the contour
// Several contours may share a slice (branches, holes: even-odd rule).
//
// dims: 2..2048 per side, at most 2^27 voxels.
//
// Method: each slice that has contours gets its 2D signed distance (to the
// polygon edges, sign by the even-odd rule; exact within two voxels of the
// contour, linear time: polygon_distance.h); between two such slices
// the field is interpolated linearly in z (shape-based interpolation); below
// the first and above the last the shape ends within one slice (a flat cap).
// The result's zero level is a closed surface; its exact 3D distance field is
// then computed from it (signed_distance.h, exact + shell).

#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sculpt/base/result.h"
#include "sculpt/core/grid/dense_grid.h"

namespace sculpt::core {

struct Contour {
  int slice = 0;
  std::vector<glm::vec2> points;
};

struct ContourStack {
  glm::ivec3 dims{0};
  std::vector<Contour> contours;
};

/// Parses the text format; errors name the line.
Result<ContourStack> parse_contours(const std::string& text);
/// Reads and parses a file; errors name the file and line.
Result<ContourStack> read_contours(const std::filesystem::path& path);

/// The interpolated level function (negative inside), voxel units.
DenseGrid<float> contour_level_function(const ContourStack& stack);
/// The signed distance field of the connected surface, voxel units.
DenseGrid<float> contour_distance_field(const ContourStack& stack, int threads = 0);

}  // namespace sculpt::core
