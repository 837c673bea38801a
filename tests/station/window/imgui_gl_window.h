#pragma once
// For the window's tests: a hidden GLFW window with an OpenGL 3.3 core
// context and an ImGui context drawing through ImGui's OpenGL backend. No
// GLFW backend: each test gives ImGui its display and input itself.

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

namespace sculpt::station::test {

class ImGuiGlWindow {
 public:
  ImGuiGlWindow(int width, int height, const char* title) {
    if (glfwInit() != GLFW_TRUE) return;
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
    window_ = glfwCreateWindow(width, height, title, nullptr, nullptr);
    if (window_ == nullptr) return;
    glfwMakeContextCurrent(window_);
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    ImGui::StyleColorsDark();
    ImGui_ImplOpenGL3_Init("#version 330 core");
  }
  ~ImGuiGlWindow() {
    if (window_ == nullptr) return;
    ImGui_ImplOpenGL3_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window_);
    glfwTerminate();
  }
  ImGuiGlWindow(const ImGuiGlWindow&) = delete;
  ImGuiGlWindow& operator=(const ImGuiGlWindow&) = delete;
  /// Null when there is no OpenGL 3.3 context.
  GLFWwindow* get() const { return window_; }

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace sculpt::station::test
