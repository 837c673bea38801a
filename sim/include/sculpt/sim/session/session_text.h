#pragma once
// The text form of a session: JSON Lines, one JSON object per line, so a
// person can read, diff and write sessions by hand, and paste captured
// reports. Converts to and from the binary form without loss (floats are
// written with enough digits to read back bit for bit).
//
// Line 1, the header:
//   {"sculpt_session": 1, "device": {"backend": "hidapi", "path": "/dev/hidraw3",
//    "name": "SpaceMouse Compact", "manufacturer": "3Dconnexion", "serial": "",
//    "vendor_product": "256f:c635", "usage_page": 1, "usage": 8,
//    "report_descriptor": "05 01 09 08 ..."}, "normalizer": "deadzone = 0.06\n...",
//    "created_unix_ns": 0}
// Every other line is one record, "t" in monotonic nanoseconds, not decreasing:
//   {"t": 1000000, "report": "01 0a 00 f6 ff 00 00"}   bytes in hex; spaces, colons
//                                                     optional (usbhid-dump output
//                                                     pastes as is); "truncated": true
//                                                     when the device sent more than 64
//   {"t": ..., "axis": [INDEX, VALUE]}   {"t": ..., "button": [INDEX, 0|1]}
//   {"t": ..., "sync": true}             {"t": ..., "removed": true}
//   {"t": ..., "cmd": "press"}  "release"  "undo"  "redo"
//   {"t": ..., "cmd": "tool", "shape": "sphere|cube|cylinder|ring|cone", "size": [A, B]}
//   {"t": ..., "cmd": "mode", "mode": "add|subtract|union|difference|smooth"}
//   {"t": ..., "cmd": "strength", "value": 0.8}    {"t": ..., "cmd": "spacing", "value": 0.25}
//   {"t": ..., "cmd": "mirror", "axis": "x|y|z|off", "at": 127.5}
//   {"t": ..., "cmd": "volume", "size": [X, Y, Z], "fill": 255}   (or "clay_margin": M)
//   {"t": ..., "cmd": "tool_pose", "position": [X, Y, Z], "orientation": [W, X, Y, Z]}
//   {"t": ..., "cmd": "pointer", "position": [X, Y, Z], "orientation": [W, X, Y, Z]}
//   {"t": ..., "cmd": "tool_from_region", "lo": [X, Y, Z], "hi": [X, Y, Z]}
//   {"t": ..., "cmd": "hypertexture", "centre": [X, Y, Z], "radius": R, "width": W, "seed": S}
// A force device's loop (see HapticRecord):
//   {"t": ..., "haptic": "start", "settings": "stiffness_n_per_mm = 1\n..."}
//   {"t": ..., "haptic": "patch", "version": 3, "centre": [X, Y, Z]}
//   {"t": ..., "haptic": "tick", "tick_t": NS, "index": I, "buttons": B, "flags": F,
//    "inputs": N, "position_mm": [X, Y, Z], "force_n": [X, Y, Z]}
// Empty lines and lines starting with # are skipped.

#include <string>
#include <string_view>

#include "sculpt/base/result.h"
#include "sculpt/sim/session/session.h"

namespace sculpt::sim {

std::string session_to_text(const Session& session);
/// Errors name the input and the line: "demo.jsonl:12: report: 'zz' is not hex".
Result<Session> session_from_text(std::string_view text, const std::string& name);

}  // namespace sculpt::sim
