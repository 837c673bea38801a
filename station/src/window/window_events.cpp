#include "window/window_events.h"

#include <imgui.h>

#include <cfloat>
#include <tuple>

namespace sculpt::station {
namespace {

// GLFW's callbacks carry no context but the window, whose user pointer is
// not ours to take (a library may use it): one watched window at a time.
WindowEvents* g_events = nullptr;

// begin_panel_frame() sets one ImGui button per kept press.
static_assert(std::tuple_size_v<decltype(WindowEvents::pressed)> <=
              sizeof(ImGuiIO::MouseDown) / sizeof(ImGuiIO::MouseDown[0]));

extern "C" void on_framebuffer_size(GLFWwindow*, int width, int height) {
  g_events->framebuffer_w = width;
  g_events->framebuffer_h = height;
}
extern "C" void on_window_size(GLFWwindow*, int width, int height) {
  g_events->window_w = width;
  g_events->window_h = height;
}
extern "C" void on_cursor_pos(GLFWwindow*, double x, double y) {
  g_events->cursor_x = x;
  g_events->cursor_y = y;
}
extern "C" void on_focus(GLFWwindow*, int focused) {
  g_events->focused = focused != 0;
}
extern "C" void on_cursor_enter(GLFWwindow*, int entered) {
  g_events->hovered = entered != 0;
}
extern "C" void on_mouse_button(GLFWwindow*, int button, int action, int) {
  if (action == GLFW_PRESS && button >= 0 && button < static_cast<int>(g_events->pressed.size()))
    g_events->pressed[static_cast<size_t>(button)] = true;
}

}  // namespace

void watch_window(GLFWwindow* window, WindowEvents* events) {
  g_events = events;
  // The round trips, once.
  glfwGetFramebufferSize(window, &events->framebuffer_w, &events->framebuffer_h);
  glfwGetWindowSize(window, &events->window_w, &events->window_h);
  glfwGetCursorPos(window, &events->cursor_x, &events->cursor_y);
  events->focused = glfwGetWindowAttrib(window, GLFW_FOCUSED) != 0;
  events->hovered = glfwGetWindowAttrib(window, GLFW_HOVERED) != 0;
  events->last_frame_s = glfwGetTime();
  glfwSetFramebufferSizeCallback(window, on_framebuffer_size);
  glfwSetWindowSizeCallback(window, on_window_size);
  glfwSetCursorPosCallback(window, on_cursor_pos);
  glfwSetWindowFocusCallback(window, on_focus);
  glfwSetCursorEnterCallback(window, on_cursor_enter);
  glfwSetMouseButtonCallback(window, on_mouse_button);
}

void begin_panel_frame(GLFWwindow* window, WindowEvents& events) {
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(events.window_w), static_cast<float>(events.window_h));
  if (events.window_w > 0 && events.window_h > 0) {
    io.DisplayFramebufferScale =
        ImVec2(static_cast<float>(events.framebuffer_w) / static_cast<float>(events.window_w),
               static_cast<float>(events.framebuffer_h) / static_cast<float>(events.window_h));
  }
  const double now_s = glfwGetTime();  // a clock, not a round trip
  io.DeltaTime = now_s > events.last_frame_s ? static_cast<float>(now_s - events.last_frame_s)
                                             : 1.0f / 60.0f;  // ImGui asks for a positive step
  events.last_frame_s = now_s;
  // GLFW keeps the buttons' states from their events (no round trip).
  for (size_t i = 0; i < events.pressed.size(); ++i) {
    io.MouseDown[i] =
        events.pressed[i] || glfwGetMouseButton(window, static_cast<int>(i)) == GLFW_PRESS;
    events.pressed[i] = false;
  }
  io.MousePos = events.focused || events.hovered ? ImVec2(static_cast<float>(events.cursor_x),
                                                          static_cast<float>(events.cursor_y))
                                                 : ImVec2(-FLT_MAX, -FLT_MAX);
}

}  // namespace sculpt::station
