#include "sculpt/core/wavelet/haar_1d.h"

#include <gtest/gtest.h>

#include <random>

namespace sculpt::core::haar {
namespace {

// The paper's example (§2.1): [9 7 3 5] -> [6 2 1 -1] and back.
TEST(Haar1d, ReproducesThePapersAveragingExample) {
  const std::vector<double> x = {9, 7, 3, 5};
  const std::vector<double> c = decompose_average(x);
  EXPECT_EQ(c, (std::vector<double>{6, 2, 1, -1}));
  EXPECT_EQ(reconstruct_average(c), x);
}

// The lifting form keeps the paper's averages and doubles its details.
TEST(Haar1d, LiftingFormHasThePapersAveragesAndDoubledDetails) {
  const std::vector<int> x = {9, 7, 3, 5};
  const std::vector<int> c = decompose_lifting(x);
  EXPECT_EQ(c, (std::vector<int>{6, 4, 2, -2}));
  EXPECT_EQ(reconstruct_lifting(c), x);
}

TEST(Haar1d, LiftingLowIsTheFloorOfTheAverage) {
  for (int a = 0; a < 256; a += 3) {
    for (int b = 0; b < 256; b += 5) {
      const LowHigh lh = lift_forward(a, b);
      EXPECT_EQ(lh.high, a - b);
      EXPECT_EQ(lh.low, (a + b) >> 1) << a << "," << b;
      const Pair p = lift_inverse(lh.low, lh.high);
      EXPECT_EQ(p.a, a);
      EXPECT_EQ(p.b, b);
    }
  }
}

TEST(Haar1d, LiftingRoundTripIsExactOnRandomSignals) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> value(0, 255);
  for (int n : {2, 8, 64, 1024}) {
    std::vector<int> x(static_cast<size_t>(n));
    for (int& v : x)
      v = value(rng);
    EXPECT_EQ(reconstruct_lifting(decompose_lifting(x)), x) << "n = " << n;
  }
}

}  // namespace
}  // namespace sculpt::core::haar
