#pragma once
// The one-euro filter (Casiez, Roussel, Vogel, CHI 2012): a low-pass whose
// cutoff rises with speed, so a still hand is steady and a fast one is not
// lagged. One filter per axis.

#include <cstdint>

namespace sculpt::hal {

struct OneEuroParams {
  float min_cutoff_hz = 1.0f;  ///< cutoff at rest, Hz: lower = steadier
  float beta = 0.05f;          ///< cutoff increase per unit/s of speed: higher = less lag
  float d_cutoff_hz = 1.0f;    ///< cutoff of the speed estimate, Hz
};

class OneEuroFilter {
 public:
  explicit OneEuroFilter(OneEuroParams params = {}) : params_(params) {}
  /// Filters x observed at t_ns. The first sample passes unchanged; a sample
  /// not later than the previous one returns the previous output.
  float filter(float x, int64_t t_ns);
  void reset() { initialised_ = false; }

 private:
  OneEuroParams params_;
  bool initialised_ = false;
  float x_prev_ = 0.0f;
  float dx_prev_ = 0.0f;
  int64_t t_prev_ns_ = 0;
};

}  // namespace sculpt::hal
