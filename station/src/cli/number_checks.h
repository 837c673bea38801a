#pragma once
// Validators for numeric command-line options. CLI11's Range and
// PositiveNumber let NaN through (every comparison with it is false) and
// accept "inf"; these refuse anything but a finite number in range.

#include <CLI/CLI.hpp>

namespace sculpt::station::cli {

/// A finite number in [lo, hi].
CLI::Validator finite_range(double lo, double hi);
/// A finite number above zero.
CLI::Validator finite_positive();

}  // namespace sculpt::station::cli
