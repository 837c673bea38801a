#pragma once
// Percentiles of a stream of durations in fixed memory. A station that runs
// for hours (the soak, a long sculpting day, a 1 kHz haptic loop) cannot keep
// every sample to sort at the end: this keeps counts in logarithmic bins, 64
// per doubling, so a percentile is within 1.1% of the exact sample's value,
// whatever the number of samples, in 21 KB. The count and the maximum are
// exact.
//
// Not thread safe: each thread keeps its own and merges.

#include <array>
#include <cstdint>

namespace sculpt {

class LatencyHistogram {
 public:
  /// Adds one duration, microseconds. Values below the first bin (about
  /// 8 ns) count in it; above the last (about 4.8 hours), in the last.
  /// NaN and negative values count as 0.
  void add(double us);
  void merge(const LatencyHistogram& other);
  void clear() { *this = LatencyHistogram(); }

  int64_t count() const { return count_; }
  double max_us() const { return max_us_; }
  /// The duration that a fraction `q` (0..1) of the samples do not exceed,
  /// to the bin's resolution and never above the exact maximum; 0 when empty.
  double quantile_us(double q) const;

  static constexpr int kBinsPerDoubling = 64;
  static constexpr int kLowestExponent = -7;  ///< 2^-7 us, about 8 ns
  static constexpr int kDoublings = 41;       ///< up to 2^34 us

 private:
  static constexpr int kBins = kBinsPerDoubling * kDoublings;
  std::array<int64_t, kBins> bins_{};
  int64_t count_ = 0;
  double max_us_ = 0;
};

}  // namespace sculpt
