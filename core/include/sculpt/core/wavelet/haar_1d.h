#pragma once
// The 1D Haar transform in the two forms the project uses.
//
// The paper ("Discrete tools for virtual sculpture" §2.1) uses the averaging
// form: a pair (a, b) becomes the average (a + b) / 2 and the detail
// (a - b) / 2, so [9 7 3 5] decomposes to [6 2 1 -1]. Its values are not
// integers in general, so it cannot hold uint8 data losslessly in integers.
//
// The volume uses the integer lifting form (the S-transform): the pair becomes
//   low  = floor((a + b) / 2)   (the paper's average, rounded down)
//   high = a - b                (twice the paper's detail)
// computed as high = a - b, low = b + floor(high / 2), and inverted exactly by
// b = low - floor(high / 2), a = b + high. [9 7 3 5] decomposes to [6 4 2 -2]:
// the same averages, details doubled. Reconstruction is bit-exact.

#include <cstdint>
#include <span>
#include <vector>

namespace sculpt::core::haar {

/// Forward S-transform of one pair: returns {low, high}.
struct LowHigh {
  int low;
  int high;
};
constexpr LowHigh lift_forward(int a, int b) {
  const int high = a - b;
  return {b + (high >> 1), high};  // >> on a negative int floors (C++20)
}
/// Inverse of lift_forward: returns {a, b}.
struct Pair {
  int a;
  int b;
};
constexpr Pair lift_inverse(int low, int high) {
  const int b = low - (high >> 1);
  return {b + high, b};
}

/// Full 1D decomposition in the paper's averaging form. `values.size()` must be
/// a power of two. Output: [coarsest average, coarsest detail, ..., finest details],
/// the paper's "final sequence".
std::vector<double> decompose_average(std::span<const double> values);
/// Inverse of decompose_average.
std::vector<double> reconstruct_average(std::span<const double> coefficients);

/// Full 1D decomposition in the integer lifting form, same layout as above.
std::vector<int> decompose_lifting(std::span<const int> values);
/// Inverse of decompose_lifting; bit-exact.
std::vector<int> reconstruct_lifting(std::span<const int> coefficients);

}  // namespace sculpt::core::haar
