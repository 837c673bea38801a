// Force to FF_CONSTANT and axis to [-1, 1]. The direction convention and its
// sources are in the header.

#include "constant_effect_mapping.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace sculpt::hal::evdev_ff {

ConstantEffectCommand constant_effect_for_force(glm::vec3 force_n, float full_scale_n,
                                                uint16_t previous_direction) {
  assert(full_scale_n > 0.0f);
  ConstantEffectCommand c;
  c.direction = previous_direction;
  const double x = force_n.x;
  const double y = force_n.y;
  if (!std::isfinite(x) || !std::isfinite(y)) return c;
  // Clamping the magnitude alone keeps the direction (the loop's safety
  // rules clamp the 3-D force; z does not reach a stick, so x/y are clamped
  // again here).
  const double magnitude = std::min(std::hypot(x, y), double(full_scale_n));
  const long level = std::lround(magnitude / full_scale_n * kMaxConstantLevel);
  if (level <= 0) return c;
  c.level = static_cast<int16_t>(std::min<long>(level, kMaxConstantLevel));
  // atan2(x, y): 0 along +y, a quarter turn along +x; then a fraction of
  // 0x10000, wrapped into 0..0xffff.
  constexpr double kTurn = 65536.0;
  const double turns = std::atan2(x, y) / (2.0 * M_PI);
  const long d = std::lround(turns * kTurn);
  c.direction = static_cast<uint16_t>(((d % 65536) + 65536) % 65536);
  return c;
}

float normalised_axis(int32_t value, const input_absinfo& range) {
  if (range.maximum <= range.minimum) return 0.0f;
  // In double: maximum - minimum may not fit an int32.
  const double span = double(range.maximum) - double(range.minimum);
  const double n = 2.0 * (double(value) - double(range.minimum)) / span - 1.0;
  return static_cast<float>(std::clamp(n, -1.0, 1.0));
}

}  // namespace sculpt::hal::evdev_ff
