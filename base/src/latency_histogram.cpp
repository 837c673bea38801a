#include "sculpt/base/latency_histogram.h"

#include <algorithm>
#include <cmath>

namespace sculpt {
namespace {

constexpr int kBins = LatencyHistogram::kBinsPerDoubling * LatencyHistogram::kDoublings;

int bin_of(double us) {
  if (!(us > 0)) return 0;
  // log2 with the fraction split into equal steps: bin i covers
  // [2^(lowest + i/64), 2^(lowest + (i+1)/64)).
  const double position =
      (std::log2(us) - LatencyHistogram::kLowestExponent) * LatencyHistogram::kBinsPerDoubling;
  if (position < 0) return 0;
  if (position >= kBins) return kBins - 1;
  return static_cast<int>(position);
}

double upper_edge_us(int bin) {
  return std::exp2(LatencyHistogram::kLowestExponent +
                   static_cast<double>(bin + 1) / LatencyHistogram::kBinsPerDoubling);
}

}  // namespace

void LatencyHistogram::add(double us) {
  if (!(us > 0)) us = 0;
  ++bins_[static_cast<size_t>(bin_of(us))];
  ++count_;
  max_us_ = std::max(max_us_, us);
}

void LatencyHistogram::merge(const LatencyHistogram& other) {
  for (size_t i = 0; i < bins_.size(); ++i)
    bins_[i] += other.bins_[i];
  count_ += other.count_;
  max_us_ = std::max(max_us_, other.max_us_);
}

double LatencyHistogram::quantile_us(double q) const {
  if (count_ == 0) return 0;
  q = std::clamp(std::isnan(q) ? 1.0 : q, 0.0, 1.0);
  // The sample of rank ceil(q * count) (at least the first), as a sort would
  // pick it; its bin's upper edge, capped by the exact maximum.
  const auto rank =
      std::max<int64_t>(1, static_cast<int64_t>(std::ceil(q * static_cast<double>(count_))));
  if (rank >= count_) return max_us_;  // the largest sample is known exactly
  int64_t seen = 0;
  for (size_t i = 0; i + 1 < bins_.size(); ++i) {
    seen += bins_[i];
    if (seen >= rank) return std::min(max_us_, upper_edge_us(static_cast<int>(i)));
  }
  return max_us_;
}

}  // namespace sculpt
