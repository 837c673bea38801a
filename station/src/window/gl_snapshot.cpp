#include "sculpt/station/window/gl_snapshot.h"

#include <cstdlib>

#include "render/gl/scene_renderer.h"
#include "sculpt/station/view/orbit_camera.h"
#include "window/gl_context.h"

namespace sculpt::station {

bool display_available() {
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  return (x11 != nullptr && *x11 != '\0') || (wayland != nullptr && *wayland != '\0');
}

Result<RgbImage> render_mesh_gl(const core::Mesh& mesh, const GlPictureView& picture) {
  return render_mesh_gl(mesh, picture, core::Tool{}, {});
}

Result<RgbImage> render_mesh_gl(const core::Mesh& mesh, const GlPictureView& picture,
                                const core::Tool& tool, std::span<const DabStandIn> stand_ins) {
  const int width = picture.width;
  const int height = picture.height;
  if (!display_available()) return Error("no display (DISPLAY is not set)");
  auto window = GlWindow::open(64, 64, "sculpt snapshot", /*visible=*/false);
  if (!window) return window.error();
  auto renderer = gl::SceneRenderer::create();
  if (!renderer) return renderer.error();

  const OffscreenTarget target(width, height);
  if (!target.complete()) return Error("the OpenGL driver cannot render off screen");
  OrbitCamera camera;
  camera.frame(picture.framed_lo, picture.framed_hi);
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  gl::SceneView view{camera.view(), camera.projection(aspect), camera.eye(), width, height};
  (*renderer)->show_mesh(mesh);
  if (!stand_ins.empty()) {
    (*renderer)->set_stand_in_tool(DabStandIns::ToolMesh::of(tool, stand_ins.front().tool_version));
  }
  gl::ToolDraw no_tool;
  no_tool.visible = false;
  (*renderer)->draw(view, no_tool, picture.block_dims, stand_ins);
  glFinish();
  RgbImage image;
  image.width = width;
  image.height = height;
  read_pixels(width, height, image.rgb);
  return image;
}

}  // namespace sculpt::station
