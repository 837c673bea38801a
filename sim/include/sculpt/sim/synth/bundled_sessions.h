#pragma once
// The sessions bundled in sim/sessions/, as the scripts that made them:
// `sculpt session generate NAME OUT` writes them again.
//
//   short  64^3 block, SpaceNavigator (split reports 1/2, bitmask buttons):
//          strokes along a line, an arc and a zig-zag, a tool and mode
//          change, an undo and a redo, an unplug and re-plug mid-stroke.
//   demo   256^3 block, SpaceMouse Compact (combined 13-byte reports): a face,
//          head, eye sockets and eyes under x-mirror symmetry, a nose ridge,
//          a smiling mouth carved along an arc, ring-tool ears, a spiral on
//          the crown, a helix-shaped curl of hair, and a stray cut undone.

#include <string>
#include <string_view>
#include <vector>

#include "sculpt/sim/session/session.h"

namespace sculpt::sim {

Session short_session();
Session demo_session();
/// The NURBS sheet: placed, dragged twice by the device, its shell added to
/// the material, then carved through.
Session sheet_session();
/// A bust in a 512^3 block with big tools (balls of 110 and 70 voxels) and
/// fine ones: the station's workload at eight times the demo's voxels.
Session bust_session();
/// The names above; nullptr-like empty optional for others.
std::vector<std::string_view> bundled_session_names();
/// The session `name` ("short", "demo", "sheet", "bust"); an empty session when unknown.
Session bundled_session(std::string_view name);
/// Where the bundled file of `name` lives in the source tree.
std::string bundled_session_path(std::string_view name);

}  // namespace sculpt::sim
