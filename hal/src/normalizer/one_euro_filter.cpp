#include "sculpt/hal/normalizer/one_euro_filter.h"

#include <cmath>

namespace sculpt::hal {
namespace {

// Smoothing factor of an exponential filter with cutoff fc at step dt.
float alpha(float cutoff_hz, float dt_s) {
  const float tau = 1.0f / (2.0f * 3.14159265f * cutoff_hz);
  return 1.0f / (1.0f + tau / dt_s);
}

}  // namespace

float OneEuroFilter::filter(float x, int64_t t_ns) {
  if (!initialised_) {
    initialised_ = true;
    x_prev_ = x;
    dx_prev_ = 0.0f;
    t_prev_ns_ = t_ns;
    return x;
  }
  if (t_ns <= t_prev_ns_) return x_prev_;
  const float dt = static_cast<float>(t_ns - t_prev_ns_) * 1e-9f;
  t_prev_ns_ = t_ns;
  const float dx = (x - x_prev_) / dt;
  const float a_d = alpha(params_.d_cutoff_hz, dt);
  dx_prev_ = a_d * dx + (1.0f - a_d) * dx_prev_;
  const float cutoff = params_.min_cutoff_hz + params_.beta * std::fabs(dx_prev_);
  const float a = alpha(cutoff, dt);
  x_prev_ = a * x + (1.0f - a) * x_prev_;
  return x_prev_;
}

}  // namespace sculpt::hal
