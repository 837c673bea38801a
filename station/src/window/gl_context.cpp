#include "window/gl_context.h"

#include <algorithm>
#include <cstdlib>
#include <mutex>
#include <string>
#include <vector>

namespace sculpt::station {
namespace {

std::string g_glfw_error;
extern "C" void on_glfw_error(int, const char* description) {
  g_glfw_error = description;
}

bool init_glfw() {
  static std::once_flag once;
  static bool ok = false;
  std::call_once(once, [] {
    glfwSetErrorCallback(on_glfw_error);
    ok = glfwInit() == GLFW_TRUE;
    if (ok) std::atexit(glfwTerminate);
  });
  return ok;
}

}  // namespace

Result<std::unique_ptr<GlWindow>> GlWindow::open(int width, int height, const std::string& title,
                                                 bool visible) {
  if (!init_glfw()) return Error("cannot start GLFW: " + g_glfw_error);
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
  // No multisampling: Mesa's software OpenGL pays for every sample, and the
  // smooth-shaded surface reads well without it.
  glfwWindowHint(GLFW_SAMPLES, 0);
  glfwWindowHint(GLFW_STENCIL_BITS, 8);  // carving stand-ins count in it (scene_renderer.cpp)
  GLFWwindow* w = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (w == nullptr) return Error("cannot open an OpenGL 3.3 window: " + g_glfw_error);
  glfwMakeContextCurrent(w);
  return std::unique_ptr<GlWindow>(new GlWindow(w));
}

GlWindow::~GlWindow() {
  glfwDestroyWindow(window_);
}

OffscreenTarget::OffscreenTarget(int width, int height) {
  glGenFramebuffers(1, &fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glGenRenderbuffers(1, &colour_);
  glBindRenderbuffer(GL_RENDERBUFFER, colour_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
  glGenRenderbuffers(1, &depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth_);
  complete_ = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
}

OffscreenTarget::~OffscreenTarget() {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteRenderbuffers(1, &colour_);
  glDeleteRenderbuffers(1, &depth_);
  glDeleteFramebuffers(1, &fbo_);
}

void read_pixels(int width, int height, std::vector<uint8_t>& rgb) {
  std::vector<uint8_t> bottom_up(static_cast<size_t>(width) * height * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, bottom_up.data());
  rgb.resize(bottom_up.size());
  const size_t row = static_cast<size_t>(width) * 3;
  for (int y = 0; y < height; ++y)
    std::copy_n(&bottom_up[static_cast<size_t>(height - 1 - y) * row], row,
                &rgb[static_cast<size_t>(y) * row]);
}

}  // namespace sculpt::station
