#include "window/pointer_steering.h"

#include <backends/imgui_impl_glfw.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "sculpt/station/view/mesh_raycast.h"
#include "sculpt/station/view/volume_raycast.h"

namespace sculpt::station {
namespace {

constexpr float kOrbitRadPerPixel = 0.008f;
constexpr float kKeyMoveVoxPerSecond = 60.0f;
constexpr float kZoomPerWheelStep = 0.9f;

PointerState* g_pointer = nullptr;  // GLFW callbacks have no user pointer to spare: ImGui uses it

extern "C" void on_scroll(GLFWwindow* w, double dx, double dy) {
  ImGui_ImplGlfw_ScrollCallback(w, dx, dy);
  if (g_pointer != nullptr && !ImGui::GetIO().WantCaptureMouse) g_pointer->scroll += dy;
}

// Where the mouse puts the tool: on the material under the cursor; in sheet
// editing, on the sheet under it, and while dragging the sheet, in the plane
// facing the view at the tool's depth.
std::optional<glm::vec3> pointer_target(const StationController& c, const Ray& ray) {
  const StationLoop& loop = c.loop();
  if (!loop.settings().sheet_editing || !loop.sheet().has_sheet())
    return raycast_surface(loop.volume(), ray);
  if (loop.sheet().dragging()) {
    return raycast_plane(ray, loop.pose().position, c.camera().forward());
  }
  return raycast_mesh(loop.sheet().mesh(), ray);
}

}  // namespace

void watch_scroll(GLFWwindow* window, PointerState* pointer) {
  g_pointer = pointer;
  if (pointer != nullptr) glfwSetScrollCallback(window, on_scroll);
}

void steer_with_pointer_and_keys(GLFWwindow* w, const WindowEvents& events, float aspect,
                                 int64_t now, int64_t last_frame, PointerState& pointer,
                                 StationController& controller, HapticStation* haptics) {
  const ImGuiIO& io = ImGui::GetIO();
  OrbitCamera& camera = controller.camera();
  const double mx = events.cursor_x, my = events.cursor_y;
  const int win_w = events.window_w, win_h = events.window_h;
  if (!io.WantCaptureMouse) {
    const bool left = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    const bool right = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    const bool middle = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
    const bool shift = glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS;
    const glm::vec2 delta(static_cast<float>(mx - pointer.x), static_cast<float>(my - pointer.y));
    if (right && !shift && pointer.orbiting)
      camera.orbit(-delta.x * kOrbitRadPerPixel, delta.y * kOrbitRadPerPixel);
    if ((middle || (right && shift)) && pointer.panning)
      camera.pan(delta, static_cast<float>(win_h));
    pointer.orbiting = right && !shift;
    pointer.panning = middle || (right && shift);
    if (pointer.scroll != 0)
      camera.zoom(std::pow(kZoomPerWheelStep, static_cast<float>(pointer.scroll)));
    pointer.scroll = 0;
    // The tool sits on the surface under the cursor; the left button sculpts.
    const glm::vec2 ndc(static_cast<float>(2.0 * mx / std::max(win_w, 1) - 1.0),
                        static_cast<float>(1.0 - 2.0 * my / std::max(win_h, 1)));
    if (left || delta != glm::vec2(0.0f)) {
      if (auto p = pointer_target(controller, camera.ray(ndc, aspect)))
        controller.pointer_move(*p, now);
    }
    if (left && !pointer.sculpting) controller.pointer_down(now);
    if (!left && pointer.sculpting) controller.pointer_up(now);
    pointer.sculpting = left;
  }
  pointer.x = mx;
  pointer.y = my;
  if (io.WantCaptureKeyboard) return;
  // Arrows move the tool in the view plane, Page Up/Down in depth; Space sculpts.
  const float step = kKeyMoveVoxPerSecond * static_cast<float>(now - last_frame) * 1e-9f;
  glm::vec3 move(0.0f);
  auto key = [&](int k) { return glfwGetKey(w, k) == GLFW_PRESS ? 1.0f : 0.0f; };
  move += camera.right() * (key(GLFW_KEY_RIGHT) - key(GLFW_KEY_LEFT));
  move += camera.up() * (key(GLFW_KEY_UP) - key(GLFW_KEY_DOWN));
  move += camera.forward() * (key(GLFW_KEY_PAGE_DOWN) - key(GLFW_KEY_PAGE_UP));
  if (move != glm::vec3(0.0f))
    controller.pointer_move(controller.loop().pose().position + move * step, now);
  const bool space = key(GLFW_KEY_SPACE) > 0;
  if (space && !pointer.space_held) controller.pointer_down(now);
  if (!space && pointer.space_held) controller.pointer_up(now);
  pointer.space_held = space;
  // V held is the clutch: a force device's (K, a shortcut, turns its force
  // on and off), else the station's, recorded when it changes.
  const bool clutch = key(GLFW_KEY_V) > 0;
  if (haptics != nullptr) {
    haptics->set_clutch(clutch);
  } else {
    controller.set_clutch(clutch, now);
  }
}

}  // namespace sculpt::station
