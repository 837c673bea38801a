#pragma once
// Replays a recorded session through the station: every raw record goes
// through the session device's real parser and normaliser (MotionPipeline),
// then the StationLoop's pose integration, stroke sampler, sculptor and mesh
// cache, in record order. Nothing depends on the pacing or the thread count,
// so the resulting volume is the same bit for bit on every replay.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "sculpt/base/latency_histogram.h"
#include "sculpt/base/result.h"
#include "sculpt/hal/types/input_event.h"
#include "sculpt/sim/session/session.h"
#include "sculpt/station/app/station_loop.h"

namespace sculpt::station {

struct ReplayOptions {
  double speed = 1.0;  ///< 1 = real time
  bool fast = false;   ///< as fast as possible
  /// Called with every normalised device event, in order (--samples).
  std::function<void(const hal::InputEvent&)> on_sample;
  /// Called with every force device's loop record, in order with the
  /// commands (haptics/haptic_replay.h); an error ends the replay.
  std::function<Status(const sim::HapticRecord&)> on_haptic;
};

struct LatencyStats {
  int64_t count = 0;
  double p50_us = 0, p90_us = 0, p99_us = 0, max_us = 0;
};

struct ReplayResult {
  int64_t records = 0;
  double wall_seconds = 0;     ///< how long the replay took
  double session_seconds = 0;  ///< the recording's own duration
  /// Per dab: from the report handed to the parser to the dab sculpted and
  /// the mesh re-made (every dab of one report shares its report's figure).
  LatencyStats dab_latency;
  int64_t unknown_reports = 0;
  int64_t short_reports = 0;
  int64_t invalid_reports = 0;  ///< dropped whole (a tracker's NaN or wrong-length bytes)
};

/// Percentiles of a set of durations in microseconds (exact).
LatencyStats latency_stats(std::vector<double> us);
/// Percentiles of a histogram of them (within its 1.1% resolution).
LatencyStats latency_stats(const LatencyHistogram& us);

/// Replays `session` into `loop`. Errors (the device has no parser, the
/// normaliser settings do not parse) name `name`.
Result<ReplayResult> replay_session(const sim::Session& session, const std::string& name,
                                    StationLoop& loop, const ReplayOptions& options = {});

}  // namespace sculpt::station
