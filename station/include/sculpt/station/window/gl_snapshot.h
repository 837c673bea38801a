#pragma once
// Pictures through OpenGL without showing a window: `sculpt replay --png`
// renders its result with the station's own GL renderer through an invisible
// GLFW window (under xvfb-run in CI, with Mesa's software OpenGL).

#include <span>

#include <glm/vec3.hpp>

#include "sculpt/base/result.h"
#include "sculpt/core/mesh/mesh.h"
#include "sculpt/core/tool/tool.h"
#include "sculpt/station/app/dab_stand_ins.h"
#include "sculpt/station/render/software_renderer.h"

namespace sculpt::station {

/// Whether an X11 or Wayland display is named in the environment.
bool display_available();

/// Renders `mesh` inside a block of `block_dims` voxels, seen from the
/// station's default camera, into a width x height picture. Errors when no
/// display or no OpenGL 3.3 context can be had.
Result<RgbImage> render_mesh_gl(const core::Mesh& mesh, glm::vec3 block_dims, int width,
                                int height);

/// The same with `stand_ins` of dabs made with `tool` drawn over it, as the
/// window draws them while the dabs wait for their meshes.
Result<RgbImage> render_mesh_gl(const core::Mesh& mesh, glm::vec3 block_dims, int width, int height,
                                const core::Tool& tool, std::span<const DabStandIn> stand_ins);

}  // namespace sculpt::station
