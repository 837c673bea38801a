#pragma once
// The station's keyboard shortcuts: GLFW key codes to the controller's
// actions. In the window, the only part that knows GLFW, so the app
// (StationController and everything below it) builds without it.

#include <optional>

#include "sculpt/station/app/station_controller.h"

namespace sculpt::station {

/// The action of a key (GLFW key code and modifier bits), if any.
std::optional<Action> shortcut(int glfw_key, int glfw_mods);
/// "Ctrl+Z" and the like, for the panel's tooltips.
const char* shortcut_label(Action action);

}  // namespace sculpt::station
