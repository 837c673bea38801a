#pragma once
// A GLFW window with an OpenGL 3.3 core context, visible or not.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "render/gl/gl_api.h"
#include "sculpt/base/result.h"

namespace sculpt::station {

class GlWindow {
 public:
  /// Initialises GLFW (once per process) and opens the window.
  static Result<std::unique_ptr<GlWindow>> open(int width, int height, const std::string& title,
                                                bool visible);
  ~GlWindow();
  GlWindow(const GlWindow&) = delete;
  GlWindow& operator=(const GlWindow&) = delete;
  GLFWwindow* handle() const { return window_; }

 private:
  explicit GlWindow(GLFWwindow* w) : window_(w) {}
  GLFWwindow* window_;
};

/// A framebuffer of its own, width x height, with colour, depth and stencil
/// (a carving stand-in counts in the stencil), bound while it lives: an
/// invisible window's own framebuffer may be smaller than asked, or not
/// exist at all. Needs a current context; the default framebuffer is bound
/// again when it goes.
class OffscreenTarget {
 public:
  OffscreenTarget(int width, int height);
  ~OffscreenTarget();
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;
  /// Whether the driver can draw into it.
  bool complete() const { return complete_; }

 private:
  GLuint fbo_ = 0, colour_ = 0, depth_ = 0;
  bool complete_ = false;
};

/// Reads the current framebuffer's colour (width x height) top row first.
void read_pixels(int width, int height, std::vector<uint8_t>& rgb);

}  // namespace sculpt::station
