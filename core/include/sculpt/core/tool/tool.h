#pragma once
// Discrete sculpting tools ("Discrete tools for virtual sculpture" §3): a tool
// is a uint8 density volume of the same model as the material, plus a pivot.
//
// The reference tool is held as a DenseGrid, not as a bricked wavelet Volume:
// tools are small (64^3 is 256 KiB) and rotation reads arbitrary voxels in its
// inner loop, where a dense array costs one load and a wavelet brick costs
// O(levels). Any Volume (or a region of it) converts to a tool in one read, so
// sculptures still become tools (the paper's key point, §3.3).

#include <cstdint>
#include <filesystem>

#include <glm/vec3.hpp>

#include "sculpt/base/result.h"
#include "sculpt/core/grid/box.h"
#include "sculpt/core/grid/dense_grid.h"
#include "sculpt/core/io/nrrd.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::core {

struct Tool {
  /// The reference (never rotated) tool: density 0..255, x fastest.
  DenseGrid<uint8_t> density;
  /// The point the tool is held and turned by, in the tool's voxel index
  /// space (voxel centres at integers; sub-voxel values allowed).
  glm::vec3 pivot{0.0f};
  /// The falloff the density was made with, in [0, 1] (see tool_density()):
  /// 1 is the hard edge of a plain shape.
  float hardness = 1.0f;
  /// A ball's radius (voxel units) when the tool is make_sphere_tool()'s
  /// ball about its pivot, else 0: a stroke then sweeps it exactly, as a
  /// capsule (stroke.h).
  float sphere_radius_vox = 0.0f;
};

/// Hardness from outside (a script, a setting): a number in [0, 1], else an
/// error naming the value.
Status check_hardness(double hardness);

/// The density of a tool voxel at signed distance `d` (voxel units, negative
/// inside) from the surface of a shape whose deepest point lies `depth_vox`
/// inside it, at `hardness` in [0, 1].
///   hardness 1: density_from_distance(d), the 2-voxel antialiased rim (today's
///     tools, bit for bit);
///   below 1: 255 smoothstep(t), t = (1 - d) / W clamped to [0, 1], over a taper
///     of W = 2 + (1 - hardness) (depth_vox - 1) voxels from the rim's outer
///     edge inwards, so hardness 0 tapers over the whole shape (a smooth bump
///     whose half-density surface lies halfway in) and the density has no
///     step anywhere.
uint8_t tool_density(float d, float depth_vox, float hardness);

/// The centre of a grid of `dims` voxels: (dims - 1) / 2.
glm::vec3 grid_centre(glm::ivec3 dims);

/// Built-in tools. Sizes are in voxels and must be positive (asserted; the
/// command line checks them). Each grid is just large enough for the shape's
/// 2-voxel density ramp; the pivot is the shape's centre.
/// `hardness` in [0, 1] (asserted) shapes the density by tool_density().
/// Ball of `radius_vox`.
Tool make_sphere_tool(float radius_vox, float hardness = 1.0f);
/// Axis-aligned cube with edges of `edge_vox`.
Tool make_cube_tool(float edge_vox, float hardness = 1.0f);
/// Cylinder along z: `radius_vox`, `height_vox`.
Tool make_cylinder_tool(float radius_vox, float height_vox, float hardness = 1.0f);
/// Ring (torus) around z: `major_radius_vox` to the tube's centre line,
/// `minor_radius_vox` of the tube.
Tool make_ring_tool(float major_radius_vox, float minor_radius_vox, float hardness = 1.0f);
/// Cone along z, base of `radius_vox` at the bottom, apex `height_vox` above.
Tool make_cone_tool(float radius_vox, float height_vox, float hardness = 1.0f);

/// The tool with its density re-made at `hardness` in [0, 1] (asserted) from
/// the signed distance of its 127.5 surface (exact, sub-voxel): any tool,
/// a file or a piece of a sculpture too. A make_sphere_tool() ball is re-made
/// from its analytic distance. Hardness 1 returns the tool unchanged; a tool
/// already softened is softened from its current surface.
Tool with_hardness(Tool tool, float hardness);

/// Any grid as a tool; pivot at its centre.
Tool tool_from_grid(DenseGrid<uint8_t> grid);
/// A region of a sculpted volume (level 0, voxels outside read 0) as a tool;
/// pivot at the region's centre.
Tool tool_from_volume(const Volume& volume, const Box& region);

/// The tool mirrored across the plane through its pivot normal to `axis`
/// (0 = x, 1 = y, 2 = z): voxel i -> dims - 1 - i, pivot likewise.
Tool mirror_tool(const Tool& tool, int axis);

/// Tool files are NRRD (uint8, x fastest) with the pivot as the key/value line
///   sculpt_pivot:=X Y Z
/// (voxel units). NRRD readers ignore key/value pairs, so a tool file is an
/// ordinary volume for every other command and program. A file without the
/// line gets its centre as pivot; a pivot more than the grid's size outside
/// the grid is refused.
Result<Tool> read_tool_nrrd(const std::filesystem::path& path, const NrrdLimits& limits = {});
Status write_tool_nrrd(const std::filesystem::path& path, const Tool& tool);

}  // namespace sculpt::core
