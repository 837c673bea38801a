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

Result<RgbImage> render_mesh_gl(const core::Mesh& mesh, glm::vec3 block, int width, int height) {
  return render_mesh_gl(mesh, block, width, height, core::Tool{}, {});
}

Result<RgbImage> render_mesh_gl(const core::Mesh& mesh, glm::vec3 block, int width, int height,
                                const core::Tool& tool, std::span<const DabStandIn> stand_ins) {
  if (!display_available()) return Error("no display (DISPLAY is not set)");
  auto window = GlWindow::open(64, 64, "sculpt snapshot", /*visible=*/false);
  if (!window) return window.error();
  auto renderer = gl::SceneRenderer::create();
  if (!renderer) return renderer.error();

  // An off-screen framebuffer of the picture's size: an invisible window's
  // own framebuffer may be smaller than asked, or not exist at all.
  GLuint fbo = 0, colour = 0, depth = 0;
  glGenFramebuffers(1, &fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glGenRenderbuffers(1, &colour);
  glBindRenderbuffer(GL_RENDERBUFFER, colour);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
  glGenRenderbuffers(1, &depth);
  glBindRenderbuffer(GL_RENDERBUFFER, depth);
  // With a stencil: a carving stand-in counts in it.
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth);
  const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;

  RgbImage image;
  if (complete) {
    OrbitCamera camera;
    camera.frame(glm::vec3(0.0f), block);
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    gl::SceneView view{camera.view(), camera.projection(aspect), camera.eye(), width, height};
    (*renderer)->show_mesh(mesh);
    if (!stand_ins.empty()) {
      (*renderer)->set_stand_in_tool(
          DabStandIns::ToolMesh::of(tool, stand_ins.front().tool_version));
    }
    gl::ToolDraw no_tool;
    no_tool.visible = false;
    (*renderer)->draw(view, no_tool, block, stand_ins);
    glFinish();
    image.width = width;
    image.height = height;
    read_pixels(width, height, image.rgb);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteRenderbuffers(1, &colour);
  glDeleteRenderbuffers(1, &depth);
  glDeleteFramebuffers(1, &fbo);
  if (!complete) return Error("the OpenGL driver cannot render off screen");
  return image;
}

}  // namespace sculpt::station
