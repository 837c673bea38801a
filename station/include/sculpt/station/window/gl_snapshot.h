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

/// What a picture shows: a block of `block_dims` voxels (its edges and the
/// ground grid under it), seen from the station's default direction by a
/// camera that frames the box framed_lo..framed_hi (OrbitCamera::frame():
/// the material in the block, as the window frames it, or the block).
struct GlPictureView {
  glm::vec3 block_dims{256.0f};
  glm::vec3 framed_lo{0.0f};
  glm::vec3 framed_hi{256.0f};
  int width = 512;
  int height = 512;
};

/// Renders `mesh` as `view` says. Errors when no display or no OpenGL 3.3
/// context can be had.
Result<RgbImage> render_mesh_gl(const core::Mesh& mesh, const GlPictureView& view);

/// The same with `stand_ins` of dabs made with `tool` drawn over it, as the
/// window draws them while the dabs wait for their meshes.
Result<RgbImage> render_mesh_gl(const core::Mesh& mesh, const GlPictureView& view,
                                const core::Tool& tool, std::span<const DabStandIn> stand_ins);

}  // namespace sculpt::station
