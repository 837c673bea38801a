#pragma once
// The two conversions between the station's units and an evdev stick:
//
// - a force in the device frame (N; x right, y up = the stick pushed away
//   from the user) to an FF_CONSTANT effect's level (0..0x7fff, 0x7fff =
//   full_scale_n) and direction (0..0xffff, a full turn);
// - an absolute axis value to [-1, 1] by the axis's absinfo range.
//
// Direction: <linux/input.h> (struct ff_effect) encodes it as 0x0000 down,
// 0x4000 left, 0x8000 up, 0xC000 right. Those name the side the force
// comes FROM, as in DirectInput: the kernel's own mixer for memoryless
// devices (drivers/input/ff-memless.c, ml_combine_effects) turns a
// constant effect into x = sin(dir) * level, y = -cos(dir) * level on the
// joystick's axes (+x right, +y toward the user), so 0x4000 pushes the stick
// right and 0x0000 pushes it away from the user; SDL's Linux haptic backend
// maps its "direction the force comes from" the same way (north, away from
// the user, to 0x8000). Hence: +x -> 0x4000, -x -> 0xC000, +y -> 0x0000,
// -y -> 0x8000, and in general direction = atan2(x, y) as a fraction of a
// turn. The level is never negative; the direction carries the sign.
//
// z is ignored: a stick has two force axes.

#include <cstdint>

#include <linux/input.h>
#include <glm/vec3.hpp>

namespace sculpt::hal::evdev_ff {

/// The largest level of an FF_CONSTANT effect (struct ff_constant_effect).
inline constexpr int16_t kMaxConstantLevel = 0x7fff;

struct ConstantEffectCommand {
  int16_t level = 0;       ///< 0..kMaxConstantLevel
  uint16_t direction = 0;  ///< 0x0000 = pushes away from the user (+y), 0x4000 = pushes right (+x)
  bool operator==(const ConstantEffectCommand&) const = default;
};

/// The effect for `force_n` (N, device frame). Its x/y magnitude is clamped
/// to full_scale_n keeping its direction; a force too small for level 1, or
/// not finite, gives level 0 and keeps `previous_direction` (so it costs no
/// update of the effect). full_scale_n > 0.
ConstantEffectCommand constant_effect_for_force(glm::vec3 force_n, float full_scale_n,
                                                uint16_t previous_direction);

/// `value` on [-1, 1]: minimum -> -1, maximum -> +1, linear between,
/// clamped (the input core does not clamp, <linux/input.h> struct
/// input_absinfo). 0 when the range is empty (maximum <= minimum).
float normalised_axis(int32_t value, const input_absinfo& range);

}  // namespace sculpt::hal::evdev_ff
