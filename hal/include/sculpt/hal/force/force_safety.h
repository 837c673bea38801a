#pragma once
// The rules that keep a force device safe (DESIGN.md §5a), applied to every
// force the haptic loop writes, whatever computed it:
// - force ramps in linearly over ramp_s when enabled, and again after any
//   interruption (a late tick, a fault);
// - zero force on the tick the loop notices a tick later than watchdog_ns,
//   a non-finite force, or a drop (a key, a device button);
// - the device's limit clamps the magnitude, keeping the direction.
//
// Deterministic: time is passed in (t_ns), so a replay in virtual time gives
// the same forces. Not thread safe: the haptic loop owns it.

#include <cstdint>

#include <glm/vec3.hpp>

#include "sculpt/hal/force/force_limits.h"

namespace sculpt::hal {

struct ForceSafetyOptions {
  /// Time for the force to grow from 0 to full after enable(), s.
  double ramp_s = 0.5;
  /// A tick this long after the previous one zeroes the force, ns.
  int64_t watchdog_ns = 3'000'000;
};

struct ForceSafetyCounters {
  int64_t watchdog_trips = 0;  ///< ticks zeroed for coming late
  int64_t non_finite = 0;      ///< forces that were NaN or infinite
  int64_t clamped = 0;         ///< forces above the device limit
  int64_t drops = 0;           ///< drop() calls that turned force off
};

class ForceSafety {
 public:
  explicit ForceSafety(const ForceLimits& limits, const ForceSafetyOptions& options = {});

  /// Turns force on; it ramps in from the next tick. No effect when on.
  void enable();
  /// Turns force off at once (until enable()).
  void drop();
  bool enabled() const { return enabled_; }
  /// The force was interrupted (a failed transfer): when on, it ramps in
  /// again from the next tick.
  void interrupt() { ramp_pending_ = enabled_; }

  /// The force to write at tick time t_ns (increasing) for `wanted_n`.
  glm::vec3 filter(glm::vec3 wanted_n, int64_t t_ns);
  /// The ramp's factor on the last filtered tick, in [0, 1].
  float ramp() const { return ramp_; }

  const ForceSafetyCounters& counters() const { return counters_; }
  const ForceLimits& limits() const { return limits_; }

 private:
  ForceLimits limits_;
  ForceSafetyOptions options_;
  bool enabled_ = false;
  bool ramp_pending_ = false;  // the ramp starts on the next tick
  int64_t ramp_start_ns_ = 0;
  bool have_last_ = false;
  int64_t last_t_ns_ = 0;
  float ramp_ = 0.0f;
  ForceSafetyCounters counters_;
};

}  // namespace sculpt::hal
