// The window's sizes, focus, cursor and clicks as GLFW's callbacks report
// them (window/window_events.h), and ImGui's frame started from them: what
// ImGui's GLFW backend would set, without asking the X server. The callbacks
// are called as glfwPollEvents() would call them, through the pointers GLFW
// holds. Without a display the test runs itself again under xvfb-run.

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <cfloat>

#include <gtest/gtest.h>

#include "imgui_gl_window.h"
#include "scratch_dir.h"
#include "sculpt/station/window/gl_snapshot.h"
#include "window/window_events.h"
#include "xvfb_rerun.h"

namespace sculpt::station {
namespace {

constexpr int kWidth = 320, kHeight = 240;

// One ImGui frame started from the events; `check` runs inside it.
template <class Check>
void panel_frame(GLFWwindow* w, WindowEvents& events, Check check) {
  ImGui_ImplOpenGL3_NewFrame();
  begin_panel_frame(w, events);
  ImGui::NewFrame();
  check(ImGui::GetIO());
  ImGui::EndFrame();
}

TEST(WindowEvents, KeepWhatTheCallbacksSayAndStartImGuisFrameFromIt) {
  if (!display_available()) {
    sculpt::test::ScratchDir dir;
    if (!sculpt::test::rerun_under_xvfb(dir)) GTEST_SKIP() << "no display and no xvfb-run";
    return;
  }
  // ImGui's OpenGL backend builds the font atlas ImGui::NewFrame() needs.
  test::ImGuiGlWindow window(kWidth, kHeight, "window events test");
  GLFWwindow* w = window.get();
  ASSERT_NE(w, nullptr) << "no OpenGL 3.3 context";
  WindowEvents events;
  watch_window(w, &events);
  // Asked once at the start: as GLFW answers.
  int ww = 0, wh = 0, fw = 0, fh = 0;
  glfwGetWindowSize(w, &ww, &wh);
  glfwGetFramebufferSize(w, &fw, &fh);
  EXPECT_EQ(events.window_w, ww);
  EXPECT_EQ(events.window_h, wh);
  EXPECT_EQ(events.framebuffer_w, fw);
  EXPECT_EQ(events.framebuffer_h, fh);

  // The callbacks watch_window() installed, as glfwPollEvents() calls them.
  const GLFWwindowsizefun window_size = glfwSetWindowSizeCallback(w, nullptr);
  const GLFWframebuffersizefun framebuffer_size = glfwSetFramebufferSizeCallback(w, nullptr);
  const GLFWcursorposfun cursor_pos = glfwSetCursorPosCallback(w, nullptr);
  const GLFWwindowfocusfun focus = glfwSetWindowFocusCallback(w, nullptr);
  const GLFWcursorenterfun cursor_enter = glfwSetCursorEnterCallback(w, nullptr);
  const GLFWmousebuttonfun mouse_button = glfwSetMouseButtonCallback(w, nullptr);
  ASSERT_TRUE(window_size && framebuffer_size && cursor_pos && focus && cursor_enter &&
              mouse_button);

  // A resize on a display of two pixels per screen coordinate.
  window_size(w, 400, 300);
  framebuffer_size(w, 800, 600);
  cursor_enter(w, GLFW_TRUE);
  cursor_pos(w, 12.0, 34.0);  // whole pixels: ImGui floors the position
  panel_frame(w, events, [](const ImGuiIO& io) {
    EXPECT_EQ(io.DisplaySize.x, 400.0f);
    EXPECT_EQ(io.DisplaySize.y, 300.0f);
    EXPECT_EQ(io.DisplayFramebufferScale.x, 2.0f);
    EXPECT_EQ(io.DisplayFramebufferScale.y, 2.0f);
    EXPECT_GT(io.DeltaTime, 0.0f);
    EXPECT_EQ(io.MousePos.x, 12.0f);
    EXPECT_EQ(io.MousePos.y, 34.0f);
    EXPECT_FALSE(io.MouseDown[0]);
  });

  // A click shorter than a frame (pressed and released between two frames)
  // is a click: down in the next frame, up in the one after.
  mouse_button(w, GLFW_MOUSE_BUTTON_LEFT, GLFW_PRESS, 0);
  mouse_button(w, GLFW_MOUSE_BUTTON_LEFT, GLFW_RELEASE, 0);
  panel_frame(w, events, [](const ImGuiIO& io) {
    EXPECT_TRUE(io.MouseDown[0]);
    EXPECT_FALSE(io.MouseDown[1]);
    EXPECT_TRUE(ImGui::IsMouseClicked(ImGuiMouseButton_Left));
  });
  panel_frame(w, events, [](const ImGuiIO& io) {
    EXPECT_FALSE(io.MouseDown[0]);
    EXPECT_TRUE(ImGui::IsMouseReleased(ImGuiMouseButton_Left));
  });

  // Neither hovered nor focused: ImGui is told the mouse is nowhere.
  cursor_enter(w, GLFW_FALSE);
  focus(w, GLFW_FALSE);
  panel_frame(w, events, [](const ImGuiIO& io) { EXPECT_EQ(io.MousePos.x, -FLT_MAX); });
  focus(w, GLFW_TRUE);
  panel_frame(w, events, [](const ImGuiIO& io) { EXPECT_EQ(io.MousePos.x, 12.0f); });
}

}  // namespace
}  // namespace sculpt::station
