#include "sculpt/core/wavelet/haar_1d.h"

#include <cassert>

namespace sculpt::core::haar {
namespace {

[[maybe_unused]] bool is_power_of_two(size_t n) {
  return n != 0 && (n & (n - 1)) == 0;
}

// Both forms share the layout: each pass halves the low-pass prefix, writing
// lows to its first half and details to its second half.
template <class T, class Step>
std::vector<T> decompose(std::span<const T> values, Step step) {
  assert(is_power_of_two(values.size()));
  std::vector<T> out(values.begin(), values.end());
  std::vector<T> scratch(out.size());
  for (size_t n = out.size(); n > 1; n /= 2) {
    for (size_t i = 0; i < n / 2; ++i)
      step(out[2 * i], out[2 * i + 1], scratch[i], scratch[n / 2 + i]);
    std::copy(scratch.begin(), scratch.begin() + static_cast<std::ptrdiff_t>(n), out.begin());
  }
  return out;
}

template <class T, class Step>
std::vector<T> reconstruct(std::span<const T> coefficients, Step step) {
  assert(is_power_of_two(coefficients.size()));
  std::vector<T> out(coefficients.begin(), coefficients.end());
  std::vector<T> scratch(out.size());
  for (size_t n = 2; n <= out.size(); n *= 2) {
    for (size_t i = 0; i < n / 2; ++i)
      step(out[i], out[n / 2 + i], scratch[2 * i], scratch[2 * i + 1]);
    std::copy(scratch.begin(), scratch.begin() + static_cast<std::ptrdiff_t>(n), out.begin());
  }
  return out;
}

}  // namespace

std::vector<double> decompose_average(std::span<const double> values) {
  return decompose(values, [](double a, double b, double& low, double& detail) {
    low = (a + b) / 2;
    detail = (a - b) / 2;
  });
}

std::vector<double> reconstruct_average(std::span<const double> coefficients) {
  return reconstruct(coefficients, [](double low, double detail, double& a, double& b) {
    a = low + detail;
    b = low - detail;
  });
}

std::vector<int> decompose_lifting(std::span<const int> values) {
  return decompose(values, [](int a, int b, int& low, int& high) {
    const LowHigh lh = lift_forward(a, b);
    low = lh.low;
    high = lh.high;
  });
}

std::vector<int> reconstruct_lifting(std::span<const int> coefficients) {
  return reconstruct(coefficients, [](int low, int high, int& a, int& b) {
    const Pair p = lift_inverse(low, high);
    a = p.a;
    b = p.b;
  });
}

}  // namespace sculpt::core::haar
