#include "sculpt/station/app/input_statistics.h"

#include <algorithm>

namespace sculpt::station {
namespace {

constexpr size_t kRecentDabs = 256;
constexpr int64_t kSecondNs = 1'000'000'000;

}  // namespace

void InputStatistics::note_dabs(int64_t count, int64_t report_t_ns, int64_t stood_in,
                                int64_t stand_in_ns, int64_t unshown) {
  stood_in = std::clamp<int64_t>(stood_in, 0, count);
  for (int64_t i = 0; i < stood_in; ++i)
    first_picture_us_.add(static_cast<double>(std::max<int64_t>(0, stand_in_ns - report_t_ns)) *
                          1e-3);
  unshown_.insert(unshown_.end(), static_cast<size_t>(stood_in), Made{report_t_ns, true});
  unshown_.insert(unshown_.end(), static_cast<size_t>(count - stood_in), Made{report_t_ns, false});
  still_unshown(unshown);
}

void InputStatistics::still_unshown(int64_t unshown) {
  while (static_cast<int64_t>(unshown_.size()) > std::max<int64_t>(0, unshown)) {
    made_.push_back(unshown_.front());
    unshown_.pop_front();
  }
}

void InputStatistics::submitted(uint64_t change, int64_t now_ns) {
  for (const Made& m : made_)
    meshing_.push_back({change, m.report_t_ns, m.pictured, now_ns});
  made_.clear();
  // A dab in the air (or one that left the voxels as they were) has nothing
  // to wait for; without this it would count until the next change meshed.
  if (change <= ready_change_) ready(ready_change_, full_detail_change_, now_ns);
}

void InputStatistics::ready(uint64_t change, uint64_t full_detail_change, int64_t ready_ns) {
  auto us = [&](const Meshing& m) { return static_cast<double>(ready_ns - m.report_t_ns) * 1e-3; };
  ready_change_ = std::max(ready_change_, change);
  full_detail_change_ = std::max(full_detail_change_, full_detail_change);
  while (!meshing_.empty() && meshing_.front().change <= change) {
    const double first = us(meshing_.front());
    detailing_.push_back(meshing_.front());
    meshing_.pop_front();
    recent_us_.push_back(first);
    if (recent_us_.size() > kRecentDabs) recent_us_.pop_front();
    all_us_.add(first);
    const Meshing& m = detailing_.back();
    note_slow({first, static_cast<double>(m.submitted_ns - m.report_t_ns) * 1e-3, m.change});
    if (!m.pictured) first_picture_us_.add(first);
  }
  while (!detailing_.empty() && detailing_.front().change <= full_detail_change) {
    full_detail_us_.add(us(detailing_.front()));
    detailing_.pop_front();
  }
}

void InputStatistics::note_slow(const SlowDab& dab) {
  // Kept sorted, slowest first; a dab slower than the last kept one takes
  // its place and sinks to its rank (eight entries: no heap needed).
  if (slowest_count_ == kSlowestKept && dab.first_mesh_us <= slowest_.back().first_mesh_us) return;
  size_t at = std::min(slowest_count_, kSlowestKept - 1);
  slowest_[at] = dab;
  slowest_count_ = std::max(slowest_count_, at + 1);
  for (; at > 0 && slowest_[at - 1].first_mesh_us < slowest_[at].first_mesh_us; --at)
    std::swap(slowest_[at - 1], slowest_[at]);
}

LatencyStats InputStatistics::recent_latency() const {
  return latency_stats({recent_us_.begin(), recent_us_.end()});
}

double InputStatistics::reader_samples(int64_t motion_samples, int64_t now_ns) {
  // Motion samples the reader decoded (dropped ones included: the device
  // sent them), averaged over about a second.
  if (!rate_started_ || motion_samples < rate_samples_) {
    rate_started_ = true;
    rate_since_ns_ = now_ns;
    rate_samples_ = motion_samples;
    return -1.0;
  }
  const int64_t dt = now_ns - rate_since_ns_;
  if (dt < kSecondNs) return -1.0;
  const double rate =
      static_cast<double>(motion_samples - rate_samples_) * 1e9 / static_cast<double>(dt);
  rate_since_ns_ = now_ns;
  rate_samples_ = motion_samples;
  return rate;
}

}  // namespace sculpt::station
