#pragma once
// Validators for command-line options: numbers, and input paths. CLI11's Range and
// PositiveNumber let NaN through (every comparison with it is false) and
// accept "inf"; these refuse anything but a finite number in range.

#include <CLI/CLI.hpp>

namespace sculpt::station::cli {

/// A finite number in [lo, hi].
CLI::Validator finite_range(double lo, double hi);
/// A finite number above zero.
CLI::Validator finite_positive();
/// An input file's path that is not a folder ("X: is a directory"): every
/// reader would otherwise open the folder and report it as an empty or
/// malformed file. A missing file is left to the reader, which names it.
CLI::Validator input_file();

}  // namespace sculpt::station::cli
