#include "sculpt/hal/normalizer/normalizer.h"

#include <algorithm>
#include <cmath>

namespace sculpt::hal {
namespace {

float apply_curve(float x, CurveKind kind, float p) {
  switch (kind) {
    case CurveKind::kLinear:
      return x;
    case CurveKind::kCubic:
      return (1.0f - p) * x + p * x * x * x;
    case CurveKind::kPower:
      return std::copysign(std::pow(std::fabs(x), p), x);
  }
  return x;
}

}  // namespace

Normalizer::Normalizer(NormalizerConfig config) : config_(config) {
  reset();
}

void Normalizer::reset() {
  for (OneEuroFilter& f : filters_)
    f = OneEuroFilter(config_.filter_params);
}

void Normalizer::apply(InputEvent& e) {
  // A tracker's pose is calibrated by the pose integrator, not by axis maps.
  if (e.kind != InputKind::kMotion || e.has_pose) return;
  const NormalizerConfig& c = config_;
  std::array<float, 6> v{};
  for (int i = 0; i < 6; ++i)
    v[i] = e.axes[c.map_source[i]] * c.map_sign[i];
  if (c.filter) {
    for (int i = 0; i < 6; ++i)
      v[i] = filters_[i].filter(v[i], e.t_ns);
  }
  if (!e.absolute) {
    for (int i = 0; i < 6; ++i) {
      // Rescaled so the output rises from 0 at the deadzone's edge instead of
      // jumping to the deadzone's value.
      const float dz = c.deadzone[i];
      const float m = std::fabs(v[i]);
      v[i] = m <= dz ? 0.0f : std::copysign((m - dz) / (1.0f - dz), v[i]);
      v[i] = apply_curve(v[i], c.curve, c.curve_param);
    }
    if (c.lock == AxisLock::kTranslation) std::fill(v.begin() + 3, v.end(), 0.0f);
    if (c.lock == AxisLock::kRotation) std::fill(v.begin(), v.begin() + 3, 0.0f);
    if (c.dominant) {
      // spacenavd's dominant mode: the largest deflection alone moves, which
      // lets a beginner push straight along one axis.
      int best = 0;
      for (int i = 1; i < 6; ++i) {
        if (std::fabs(v[i]) > std::fabs(v[best])) best = i;
      }
      for (int i = 0; i < 6; ++i) {
        if (i != best) v[i] = 0.0f;
      }
    }
  }
  for (int i = 0; i < 6; ++i)
    e.axes[i] = std::clamp(v[i] * c.sensitivity[i], -1.0f, 1.0f);
}

}  // namespace sculpt::hal
