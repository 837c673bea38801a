#pragma once
// Pictures through OpenGL without showing a window: `sculpt replay --png`
// renders its result with the station's own GL renderer through an invisible
// GLFW window (under xvfb-run in CI, with Mesa's software OpenGL).

#include <glm/vec3.hpp>

#include "sculpt/base/result.h"
#include "sculpt/core/mesh/mesh.h"
#include "sculpt/station/render/software_renderer.h"

namespace sculpt::station {

/// Whether an X11 or Wayland display is named in the environment.
bool display_available();

/// Renders `mesh` inside a block of `block_dims` voxels, seen from the
/// station's default camera, into a width x height picture. Errors when no
/// display or no OpenGL 3.3 context can be had.
Result<RgbImage> render_mesh_gl(const core::Mesh& mesh, glm::vec3 block_dims, int width,
                                int height);

}  // namespace sculpt::station
