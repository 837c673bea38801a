#pragma once
// What the window knows of itself without asking the X server.
//
// GLFW's getters for a window's size, focus and cursor are X round trips:
// under Xvfb beside llvmpipe on two cores, 0.1-12 ms each, and a frame made
// nine of them (its own three, five in ImGui's GLFW backend), 0.6-0.75 ms a
// frame on average. The X server sends the same facts as events, which
// GLFW hands to callbacks in glfwPollEvents(): WindowEvents keeps them, and
// begin_panel_frame() starts ImGui's frame from them, as the backend's
// ImGui_ImplGlfw_NewFrame() would but without a round trip.
//
// Thread safety: the window's thread (GLFW runs the callbacks there).

#include <array>

#include "render/gl/gl_api.h"

namespace sculpt::station {

struct WindowEvents {
  int framebuffer_w = 1, framebuffer_h = 1;  // pixels
  int window_w = 1, window_h = 1;            // screen coordinates
  double cursor_x = 0.0, cursor_y = 0.0;     // screen coordinates, from the window's corner
  bool focused = false;
  bool hovered = false;  // the cursor is over the window
  /// Mouse buttons pressed since the panel's last frame: a click shorter
  /// than a frame still reaches the panel.
  std::array<bool, 5> pressed{};
  double last_frame_s = 0.0;  // glfwGetTime() at the panel's last frame
};

/// Asks the window's state once and keeps it up to date from GLFW's
/// callbacks. Call before ImGui_ImplGlfw_InitForOpenGL(): ImGui's backend
/// passes the focus, cursor-enter and button events it takes on to these.
/// One window at a time; `events` must outlive the window's callbacks.
void watch_window(GLFWwindow* window, WindowEvents* events);

/// Sets ImGui's display size, time step, mouse position and buttons for a
/// new frame, in place of ImGui_ImplGlfw_NewFrame() (whose cursor shapes
/// and gamepads the panel does not use).
void begin_panel_frame(GLFWwindow* window, WindowEvents& events);

}  // namespace sculpt::station
