#pragma once
// How the device feels: the user's normaliser settings and their text file.
//
// File format (UTF-8 text, one `key = value` per line, `#` starts a comment,
// keys in any order, every key optional; axis names tx ty tz rx ry rz):
//   deadzone = 0.06              # all axes, fraction of full deflection [0, 0.9]
//   deadzone.rz = 0.1            # one axis
//   sensitivity = 1.0            # all axes, multiplier (0, 10]
//   sensitivity.translation = 1.0
//   sensitivity.rotation = 0.8
//   sensitivity.tx = 1.0         # one axis
//   curve = cubic 0.6            # linear | cubic K (K in [0,1]: y = (1-K)x + Kx^3) | power P (P in
//   [1,4]) map = tx ty tz rx ry rz      # output axis i <- named input axis, '-' inverts: "tx -tz
//   ty rx -rz ry" lock = none                  # none | translation (translation only) | rotation
//   (rotation only) dominant = off               # on: only the largest axis moves filter = on #
//   one-euro filter on | off filter.min_cutoff_hz = 1.0 filter.beta = 0.05 filter.d_cutoff_hz = 1.0

#include <array>
#include <string>
#include <string_view>

#include "sculpt/base/result.h"
#include "sculpt/hal/normalizer/one_euro_filter.h"

namespace sculpt::hal {

enum class CurveKind : uint8_t { kLinear, kCubic, kPower };
enum class AxisLock : uint8_t { kNone, kTranslation, kRotation };

struct NormalizerConfig {
  std::array<float, 6> deadzone{0.06f, 0.06f, 0.06f, 0.06f, 0.06f, 0.06f};
  std::array<float, 6> sensitivity{1, 1, 1, 1, 1, 1};
  /// A cubic blend gives fine control near rest and full speed at full
  /// deflection: what 3D-mouse users expect.
  CurveKind curve = CurveKind::kCubic;
  float curve_param = 0.5f;
  std::array<uint8_t, 6> map_source{0, 1, 2, 3, 4, 5};
  std::array<int8_t, 6> map_sign{1, 1, 1, 1, 1, 1};
  AxisLock lock = AxisLock::kNone;
  bool dominant = false;
  bool filter = true;
  OneEuroParams filter_params{};
};

/// Parses the text form. `name` names the input in errors:
/// "input.conf:4: curve: expected linear, cubic K or power P, got 'quadratic'".
Result<NormalizerConfig> parse_normalizer_config(std::string_view text, const std::string& name);

/// Reads and parses a config file.
Result<NormalizerConfig> load_normalizer_config(const std::string& path);

/// Where the station looks for the user's file: $SCULPT_INPUT_CONFIG if set,
/// else $XDG_CONFIG_HOME/sculpt/input.conf, else ~/.config/sculpt/input.conf.
std::string default_normalizer_config_path();

/// Loads `path` when it exists; a missing file gives the defaults (nothing to
/// tune yet), a broken one an Error naming file and line.
Result<NormalizerConfig> load_normalizer_config_or_defaults(const std::string& path);

/// The text form of a config (parse_normalizer_config reads it back equal).
std::string to_text(const NormalizerConfig& config);

}  // namespace sculpt::hal
