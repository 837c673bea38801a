#pragma once
// Any tool made larger or smaller: a sculpture turned into a tool, a tool
// file, a region, at another size (the discrete-tools paper's tools are
// volumes; a sculptor wants them at the size the work needs).

#include "sculpt/core/tool/tool.h"

namespace sculpt::core {

/// Smallest and largest scale factor scale_tool() takes.
inline constexpr float kMinToolScale = 0.125f;
inline constexpr float kMaxToolScale = 8.0f;

/// The grid scale_tool() makes of `dims` voxels: round(dims * factor), at
/// least 1 (check it against a size limit before scaling).
glm::ivec3 scaled_tool_dims(glm::ivec3 dims, float factor);

/// `tool` scaled by `factor` in [kMinToolScale, kMaxToolScale] about its
/// grid's corner: the grid becomes round(dims * factor) voxels (at least 1),
/// each voxel the trilinear sample of the original at the point it covers
/// (zero outside the grid, as the antialiased rotation samples; the float
/// fields' sample_trilinear() clamps instead, which would smear a rim),
/// and the pivot follows, so a scaled tool is held at the same point of its
/// shape. Its volume (density sum) scales by factor^3 within 1% for shapes
/// a few voxels across or more. Hardness is kept; a ball's exact radius is
/// not (the stroke then sweeps it as a grid tool).
Tool scale_tool(const Tool& tool, float factor);

}  // namespace sculpt::core
