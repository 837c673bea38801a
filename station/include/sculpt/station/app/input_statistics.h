#pragma once
// What the station measures of its input as it runs: each dab's latency
// from its device report to its mesh ready to draw, and the device's report
// rate. The panel shows the recent figures, --stats the whole session's.
//
// A dab's latency is known only when the mesher says the change holding it
// is meshed, so dabs pass four stages: made (note_dabs), handed to the
// mesher as change N (submitted), first meshed (up to change N, maybe
// coarse), and meshed at full detail. Both latencies are kept, and a third:
// to the dab's first picture, which is its stand-in's when one showed it
// before it was sculpted (dab_stand_ins.h), else its first mesh.
//
// Thread safety: one thread (the station's main loop).

#include <array>
#include <cstdint>
#include <deque>
#include <span>
#include <vector>

#include "sculpt/base/latency_histogram.h"
#include "sculpt/station/app/session_replay.h"

namespace sculpt::station {

class InputStatistics {
 public:
  /// `count` dabs were made from a report read at `report_t_ns`, of which
  /// `stood_in` (the first ones) were shown by stand-ins published at
  /// `stand_in_ns`; `unshown` of the dabs made so far (the newest) changed
  /// nothing yet and wait for a later change (still_unshown()).
  void note_dabs(int64_t count, int64_t report_t_ns, int64_t stood_in = 0, int64_t stand_in_ns = 0,
                 int64_t unshown = 0);
  /// Of the dabs held as unshown, all but the newest `unshown` are in the
  /// next change: a ball brush's dabs wait for the preview that shows them
  /// (or the press's end), not for nothing.
  void still_unshown(int64_t unshown);
  /// Whether dabs were made since the last submitted().
  bool dabs_waiting() const { return !made_.empty(); }
  /// At `now_ns`, the dabs made so far went to the mesher as change
  /// `change`. A change already meshed (the mesher had nothing new: the
  /// dabs touched no voxel) shows them at once.
  void submitted(uint64_t change, int64_t now_ns);
  /// At `ready_ns`, every change up to `change` was meshed, and every
  /// change up to `full_detail_change` at full detail.
  void ready(uint64_t change, uint64_t full_detail_change, int64_t ready_ns);

  /// Latency of the last few hundred dabs (exact), and of all (histogram).
  LatencyStats recent_latency() const;
  LatencyStats session_latency() const { return latency_stats(all_us_); }
  /// Report to full detail on screen, the whole session.
  LatencyStats full_detail_latency() const { return latency_stats(full_detail_us_); }
  /// Report to the first picture of the dab (stand-in or mesh), the whole session.
  LatencyStats first_picture_latency() const { return latency_stats(first_picture_us_); }

  /// One of the session's slowest dabs to a first mesh, split where the
  /// time went: report -> handed to the mesher (reading, ordering and
  /// sculpting), then -> its change's first mesh ready to draw (meshing).
  struct SlowDab {
    double first_mesh_us = 0;
    double handed_over_us = 0;
    uint64_t change = 0;
  };
  static constexpr size_t kSlowestKept = 8;
  /// The slowest dabs so far, slowest first (at most kSlowestKept): the
  /// few that set a p99 are named, not only counted.
  std::span<const SlowDab> slowest() const { return {slowest_.data(), slowest_count_}; }

  /// The reader's count of motion samples so far; returns the report rate
  /// over about the last second once one has passed, else a negative value.
  double reader_samples(int64_t motion_samples, int64_t now_ns);
  /// The device went: the next rate counts from its next samples.
  void restart_report_rate() { rate_started_ = false; }

 private:
  struct Made {
    int64_t report_t_ns;
    bool pictured;  // its first picture (a stand-in) is counted already
  };
  struct Meshing {
    uint64_t change;
    int64_t report_t_ns;
    bool pictured;
    int64_t submitted_ns;
  };
  void note_slow(const SlowDab& dab);
  std::deque<Made> unshown_;       // dabs that changed nothing yet, oldest first
  std::vector<Made> made_;         // dabs not yet submitted
  std::deque<Meshing> meshing_;    // submitted, waiting for their meshes
  std::deque<Meshing> detailing_;  // shown, waiting for full detail
  uint64_t ready_change_ = 0;      // the last ready() figures
  uint64_t full_detail_change_ = 0;
  std::deque<double> recent_us_;
  LatencyHistogram all_us_;  // fixed memory: the station runs for hours
  LatencyHistogram full_detail_us_;
  LatencyHistogram first_picture_us_;
  std::array<SlowDab, kSlowestKept> slowest_{};
  size_t slowest_count_ = 0;
  bool rate_started_ = false;
  int64_t rate_since_ns_ = 0;
  int64_t rate_samples_ = 0;
};

}  // namespace sculpt::station
