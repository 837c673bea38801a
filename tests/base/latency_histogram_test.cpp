#include "sculpt/base/latency_histogram.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace sculpt {
namespace {

TEST(LatencyHistogram, EmptyIsZero) {
  LatencyHistogram h;
  EXPECT_EQ(h.count(), 0);
  EXPECT_EQ(h.quantile_us(0.99), 0.0);
  EXPECT_EQ(h.max_us(), 0.0);
}

TEST(LatencyHistogram, PercentilesWithinOnePercentOfTheSortedSamples) {
  // Log-normal durations over six decades, as frame and dab times spread.
  std::mt19937_64 random(7);
  std::lognormal_distribution<double> duration(std::log(800.0), 2.0);
  std::vector<double> samples(200000);
  LatencyHistogram h;
  for (double& s : samples) {
    s = duration(random);
    h.add(s);
  }
  std::sort(samples.begin(), samples.end());
  for (double q : {0.01, 0.5, 0.9, 0.99, 0.999}) {
    const double exact =
        samples[static_cast<size_t>(std::ceil(q * static_cast<double>(samples.size()))) - 1];
    EXPECT_GE(h.quantile_us(q), exact) << q;  // the bin's upper edge
    EXPECT_LE(h.quantile_us(q), exact * 1.011) << q;
  }
  EXPECT_EQ(h.count(), 200000);
  EXPECT_EQ(h.max_us(), samples.back());
  EXPECT_EQ(h.quantile_us(1.0), samples.back());
}

TEST(LatencyHistogram, MemoryDoesNotGrowWithSamples) {
  // The point of it: a day of 1 kHz ticks costs what one tick does.
  static_assert(sizeof(LatencyHistogram) < 24 * 1024);
  LatencyHistogram h;
  for (int i = 0; i < 1000000; ++i)
    h.add(1000.0 + (i % 7));
  EXPECT_EQ(h.count(), 1000000);
  EXPECT_NEAR(h.quantile_us(0.5), 1003.0, 1003.0 * 0.011);
}

TEST(LatencyHistogram, OutsideValuesCountAtTheEnds) {
  LatencyHistogram h;
  h.add(std::numeric_limits<double>::quiet_NaN());
  h.add(-5.0);
  h.add(0.0);
  h.add(1e-6);
  h.add(1e12);  // beyond the last bin: counted there, the maximum exact
  EXPECT_EQ(h.count(), 5);
  EXPECT_LT(h.quantile_us(0.8), 0.01);
  EXPECT_EQ(h.quantile_us(1.0), 1e12);
  EXPECT_EQ(h.max_us(), 1e12);
}

TEST(LatencyHistogram, MergeEqualsAddingEverything) {
  LatencyHistogram a, b, all;
  for (int i = 1; i <= 1000; ++i) {
    (i % 3 ? a : b).add(i * 1.5);
    all.add(i * 1.5);
  }
  a.merge(b);
  EXPECT_EQ(a.count(), all.count());
  EXPECT_EQ(a.max_us(), all.max_us());
  for (double q : {0.1, 0.5, 0.99})
    EXPECT_EQ(a.quantile_us(q), all.quantile_us(q));
}

}  // namespace
}  // namespace sculpt
