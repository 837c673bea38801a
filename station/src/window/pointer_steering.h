#pragma once
// The ordinary mouse and keyboard: the camera orbits, pans and zooms, the
// tool follows the cursor onto the clay (or the sheet being edited) and
// the left button or Space sculpts; arrows and Page Up/Down move the tool,
// V is the clutch.
//
// Thread safety: the window's thread, with the frame's turn (input_hub.h):
// it steers the controller.

#include <cstdint>

#include "render/gl/gl_api.h"
#include "sculpt/station/app/station_controller.h"
#include "sculpt/station/haptics/haptic_station.h"
#include "window/window_events.h"

namespace sculpt::station {

/// What the mouse and keyboard were doing at the last frame that steered.
struct PointerState {
  bool orbiting = false;
  bool panning = false;
  bool sculpting = false;
  bool space_held = false;
  double x = 0, y = 0;  // the cursor, screen coordinates
  double scroll = 0;    // wheel steps since then (watch_scroll)
};

/// Adds the wheel's steps to `pointer` (when the panel does not take them)
/// and passes them on to ImGui's backend; call after ImGui's backend has
/// installed its callbacks. One window at a time; `pointer` must outlive
/// the window's callbacks, or null stops counting.
void watch_scroll(GLFWwindow* window, PointerState* pointer);

/// One frame's steering, from the window's events and GLFW's key and
/// button states; the panel keeps the mouse and keys it wants (ImGui's
/// WantCaptureMouse, WantCaptureKeyboard). `now_ns` and `last_frame_ns`
/// time the keys' moves; `aspect` is the framebuffer's. A force device, when
/// there is one, takes the clutch.
void steer_with_pointer_and_keys(GLFWwindow* window, const WindowEvents& events, float aspect,
                                 int64_t now_ns, int64_t last_frame_ns, PointerState& pointer,
                                 StationController& controller, HapticStation* haptics);

}  // namespace sculpt::station
