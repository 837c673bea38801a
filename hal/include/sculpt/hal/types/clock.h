#pragma once
// The one clock of the input pipeline (DESIGN.md §3): int64 nanoseconds on a
// monotonic clock. A replay never calls it; it uses the recorded times.

#include <cstdint>

namespace sculpt::hal {

/// Nanoseconds since an arbitrary fixed point (CLOCK_MONOTONIC). Thread-safe.
int64_t monotonic_ns();
/// Sleeps until monotonic_ns() reaches `t_ns` (at once if it has).
void sleep_until_ns(int64_t t_ns);

}  // namespace sculpt::hal
