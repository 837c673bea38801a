#include "cli/number_checks.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "sculpt/base/input_file.h"

namespace sculpt::station::cli {
namespace {

CLI::Validator finite_check(const std::string& what, bool (*ok)(double, double, double), double lo,
                            double hi) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double v = 0.0;
        if (!CLI::detail::lexical_cast(text, v) || !std::isfinite(v) || !ok(v, lo, hi))
          return "value " + text + " is not a number " + what;
        return {};
      },
      what);
}

}  // namespace

CLI::Validator finite_range(double lo, double hi) {
  char range[64];
  std::snprintf(range, sizeof range, "in [%g, %g]", lo, hi);
  return finite_check(
      range, [](double v, double l, double h) { return v >= l && v <= h; }, lo, hi);
}

CLI::Validator finite_positive() {
  return finite_check(
      "above 0", [](double v, double, double) { return v > 0.0; }, 0.0, 0.0);
}

CLI::Validator input_file() {
  return CLI::Validator(
      [](std::string& path) -> std::string {
        if (const Status s = check_input_file(path); !s) return s.error().message();
        return {};
      },
      "FILE");
}

}  // namespace sculpt::station::cli
