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
/// An input file's path that names no folder, FIFO, device or socket
/// (check_input_file(): "X: is a directory"): a reader would otherwise report
/// a folder as an empty or malformed file, and wait for ever on a FIFO with
/// no writer. A missing file is left to the reader, which names it.
CLI::Validator input_file();

}  // namespace sculpt::station::cli
