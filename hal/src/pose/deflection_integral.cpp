#include "sculpt/hal/pose/deflection_integral.h"

namespace sculpt::hal {

void DeflectionIntegral::accumulate(InputEvent& e) {
  if (e.kind != InputKind::kMotion || e.absolute) return;
  if (have_prev_ && e.t_ns > prev_t_ns_) {
    const int64_t gap = e.t_ns - prev_t_ns_;
    if (gap > max_gap_ns_) {
      const double dt = static_cast<double>(max_gap_ns_) * 1e-9;
      for (int i = 0; i < kAxisCount; ++i)
        integral_[i] += double{prev_[i]} * dt;
    } else {
      const double dt = static_cast<double>(gap) * 1e-9;
      for (int i = 0; i < kAxisCount; ++i)
        integral_[i] += 0.5 * (double{prev_[i]} + e.axes[i]) * dt;
    }
  }
  if (!have_prev_ || e.t_ns > prev_t_ns_) {
    prev_ = e.axes;
    prev_t_ns_ = e.t_ns;
    have_prev_ = true;
  }
  e.integral = integral_;
}

}  // namespace sculpt::hal
