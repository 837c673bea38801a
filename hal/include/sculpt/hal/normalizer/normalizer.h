#pragma once
// Turns parsed motion into what the user meant, in one place after the
// parser (spacenavd's model). For each motion sample, in this order:
// axis map and inversion, one-euro filter, deadzone (rescaled so the output
// starts from 0 at its edge), response curve, translation/rotation lock,
// dominant axis, sensitivity, clamp to [-1, 1]. Absolute samples (trackers)
// get only the map and the filter: a deadzone would bend a position.

#include "sculpt/hal/normalizer/normalizer_config.h"
#include "sculpt/hal/types/input_event.h"

namespace sculpt::hal {

class Normalizer {
 public:
  explicit Normalizer(NormalizerConfig config = {});
  /// Normalises a kMotion event in place; other kinds pass unchanged.
  void apply(InputEvent& event);
  const NormalizerConfig& config() const { return config_; }
  /// Forgets filter state (after a reconnect).
  void reset();

 private:
  NormalizerConfig config_;
  std::array<OneEuroFilter, 6> filters_;
};

}  // namespace sculpt::hal
