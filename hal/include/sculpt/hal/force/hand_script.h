#pragma once
// The scripted hand that holds the simulated arm (force/sim_arm.h): where it
// wants the grip to be over time, how firmly it holds, which buttons it
// presses and when it pulls the plug. CI's closed loop and the bundled
// `touch` session are driven by these.
//
// The text form, one statement per line, '#' starts a comment:
//
//   sculpt-hand 1                  first line: the format and its version
//   grip 0.5 4                     the hand's spring (N/mm) and damping (N·s/m)
//   at 0.0  0 20 0                 at time t (s) the hand aims at x y z (mm, device frame)
//   at 0.5  0 -5 0                 targets between `at` lines are linear; after the last, held
//   buttons 1.0 1                  from time t (s) the buttons in the mask are held
//   unplug 2.0                     the arm is unplugged at time t (s)
//
// Times must not decrease within `at` lines or within `buttons` lines; every
// number must be finite; positions within 1000 mm; at least one `at` line.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/base/result.h"

namespace sculpt::hal {

struct HandWaypoint {
  double t_s = 0.0;
  glm::vec3 target_mm{0.0f};
};

struct HandButtons {
  double t_s = 0.0;
  uint32_t mask = 0;
};

struct HandScript {
  /// The hand's grip: a spring toward the target, N/mm, and a damper, N·s/m.
  float stiffness_n_per_mm = 0.5f;
  float damping_ns_per_m = 4.0f;
  std::vector<HandWaypoint> path;
  std::vector<HandButtons> buttons;
  /// When the arm is unplugged, s; negative: never.
  double unplug_s = -1.0;

  /// The target at time t_s (linear between waypoints, held outside them).
  glm::vec3 target_at(double t_s) const;
  /// The buttons held at time t_s.
  uint32_t buttons_at(double t_s) const;
  /// The last time anything in the script happens, s.
  double end_s() const;
};

/// Parses the text form; errors name `source` and the line.
Result<HandScript> parse_hand_script(std::string_view text, const std::string& source);
/// Reads and parses a file.
Result<HandScript> read_hand_script(const std::string& path);

}  // namespace sculpt::hal
