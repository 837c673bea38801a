#pragma once
// Runs a recorded force device's loops again (haptic_recording.h): each
// recorded tick goes through a new HapticLoop, ContactForceLaw and safety
// rules in virtual time, on patches built again from the replayed material,
// and the force it gives is compared with the one recorded, bit for bit.
//
// Used by the session replay (session_replay.h, ReplayOptions::on_haptic),
// which hands over the haptic records in order with the commands, so that
// the material a patch record is built from is the one the live sculpting
// side read.
//
// A loop whose start is not in the recording, or whose ticks have a gap (the
// sculpting side fell 4096 ticks behind), cannot be run again: its ticks are
// counted as unverified instead of compared.

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>

#include "sculpt/base/latency_histogram.h"
#include "sculpt/base/result.h"
#include "sculpt/core/haptics/patch_exchange.h"
#include "sculpt/core/haptics/patch_keeper.h"
#include "sculpt/hal/haptics/haptic_loop.h"
#include "sculpt/sim/session/session.h"
#include "sculpt/station/app/station_loop.h"
#include "sculpt/station/haptics/contact_force_law.h"
#include "sculpt/station/haptics/haptic_recording.h"

namespace sculpt::station {

/// What `replay --stats` reports of the haptic loops.
struct HapticReplayFigures {
  int64_t loops = 0;
  int64_t ticks = 0;  ///< run again and compared
  /// Ticks whose force differs from the recorded one in any bit.
  int64_t force_mismatches = 0;
  /// Ticks that could not be run again (no start, a gap).
  int64_t unverified_ticks = 0;
  int64_t patches = 0;
  /// Patches rebuilt with another version than the live one.
  int64_t patch_mismatches = 0;
  /// Periods between the recorded ticks: over 1.5 ms, the worst, the p99, us.
  int64_t late_ticks = 0;
  double worst_period_us = 0.0;
  double period_p99_us = 0.0;
  float max_force_n = 0.0f;
};

/// One tick run again: the recorded reading and the force the replay gave.
struct ReplayedTick {
  int64_t loop = 0;            ///< 0, 1, ... in recording order
  hal::HapticTickRecord tick;  ///< as replayed (force_n is the replay's)
  ContactRecord contact;       ///< what the law did (proxy, contact, normal)
  bool matches = true;         ///< force_n equals the recorded force bit for bit
};

class HapticReplay {
 public:
  /// `material`: the replay's station, whose volume the patches are built from.
  HapticReplay(const StationLoop& material, std::string name);
  ~HapticReplay();

  /// Called with every tick run again, in order.
  std::function<void(const ReplayedTick&)> on_tick;

  /// One haptic record. Errors: a start record whose set-up does not parse
  /// (naming the session).
  Status handle(const sim::HapticRecord& record);
  /// The figures so far.
  HapticReplayFigures figures() const;

 private:
  class Device;
  struct Loop;
  void tick(const sim::HapticRecord& record);
  // Makes the patch of `version` the newest in the loop's exchange; false
  // when the recording did not publish it.
  bool offer_patch(uint64_t version);

  const StationLoop& material_;
  std::string name_;
  std::unique_ptr<Loop> loop_;
  HapticReplayFigures figures_;
  LatencyHistogram periods_us_;
  int64_t last_tick_ns_ = 0;
  bool have_last_tick_ = false;
};

}  // namespace sculpt::station
