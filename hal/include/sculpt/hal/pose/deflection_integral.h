#pragma once
// Integrates a rate device's deflection over the sample times, on the reader
// side of the ring, so that the main loop, which sees only the newest sample
// (motion is state), still moves the tool by everything the device reported.
// Between two samples the deflection is taken as the average of both
// (trapezoid); across a gap longer than max_gap_ns the device was silent
// (3D mice stop reporting at rest), so the earlier deflection is held for at
// most max_gap_ns.

#include <cstdint>

#include "sculpt/hal/types/input_event.h"

namespace sculpt::hal {

class DeflectionIntegral {
 public:
  explicit DeflectionIntegral(int64_t max_gap_ns = 50'000'000) : max_gap_ns_(max_gap_ns) {}
  /// Sets event.integral for a relative kMotion event; other events pass.
  void accumulate(InputEvent& event);
  void reset() {
    have_prev_ = false;
    integral_ = {};
  }

 private:
  int64_t max_gap_ns_;
  bool have_prev_ = false;
  int64_t prev_t_ns_ = 0;
  std::array<float, kAxisCount> prev_{};
  std::array<double, kAxisCount> integral_{};
};

}  // namespace sculpt::hal
