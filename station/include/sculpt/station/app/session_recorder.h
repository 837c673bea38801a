#pragma once
// Records what the station does into a session file while it runs: the raw
// reports of the device (handed over from its reader thread) and every
// station command (from the UI), merged in time order. The file is appended
// as it goes and synced at least every 0.25 s, so a crash loses at most that.
//
// Thread safety: raw() may be called from any thread (the reader's raw tap);
// everything else from the main loop.

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "sculpt/base/result.h"
#include "sculpt/sim/session/session_file.h"

namespace sculpt::station {

class SessionRecorder {
 public:
  /// Starts a recording in `path` (replacing it) whose first records are
  /// `opening` (the commands that rebuild the station's current settings).
  Status start(const std::filesystem::path& path, const sim::SessionHeader& header,
               const std::vector<sim::Command>& opening, int64_t now_ns);
  bool recording() const { return writer_.has_value(); }
  /// Keeps raw events from now on for a start() to come: so a recording asked
  /// for before the devices open misses none of their first reports.
  void arm() {
    armed_.store(true);
    accepting_.store(true);
  }
  const std::filesystem::path& path() const { return path_; }

  /// A station command, at `t_ns` (monotonic).
  void command(const sim::Command& command, int64_t t_ns);
  /// A force device's loop record, at `t_ns` (monotonic), after the
  /// commands given before it.
  void haptic(const sim::HapticRecord& record, int64_t t_ns) {
    if (writer_) pending_.push_back(sim::SessionRecord::of(t_ns, record));
  }
  /// A raw device event (any thread).
  void raw(const hal::RawEvent& event);
  /// Raw events up to `t_ns` may be written: the station has applied them.
  /// (The reader thread taps events before the main loop takes them from
  /// its ring; writing one early could put it before a command the station
  /// applied first.) Until the first call, every event may be written.
  void release_until(int64_t t_ns) { released_t_ns_ = t_ns; }
  /// Writes the commands and the released raw events, in time order; syncs
  /// when due. An error stops the recording (what was written stays readable).
  Status flush();
  /// Flushes and closes; returns the records written.
  Result<int64_t> stop();

 private:
  // Closes the writer (if any) and drops the raw events waiting.
  void stop_accepting();
  std::optional<sim::SessionWriter> writer_;
  std::filesystem::path path_;
  std::vector<sim::SessionRecord> pending_;  // main thread's commands
  std::mutex raw_mutex_;
  std::vector<hal::RawEvent> raw_;  // from the reader thread
  std::atomic<bool> armed_{false};  // keep raw events while not yet recording
  // Whether raw() keeps events at all (recording or armed): a device read
  // while nothing records must not pile its events up here.
  std::atomic<bool> accepting_{false};
  int64_t last_t_ns_ = 0;
  int64_t released_t_ns_ = std::numeric_limits<int64_t>::max();
};

}  // namespace sculpt::station
