#pragma once
// Records what the station does into a session file while it runs: the raw
// reports of the device (handed over from its reader thread) and every
// station command (from the UI), merged in time order. The file is appended
// as it goes and synced at least every 0.25 s, so a crash loses at most that.
//
// A file holds exactly the reports the station applied while it recorded:
// a report tapped but not yet applied when a recording starts goes into it
// (the station applies it after the opening), one still in flight when it
// stops does not. So between recordings the reports in flight are kept,
// and the applied ones let go (release_until()).
//
// Thread safety: raw() may be called from any thread (the reader's raw tap);
// everything else from the main loop.

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
  /// Raw events up to `t_ns` are applied: a recording may write them, and
  /// while none runs they are let go. (The reader thread taps events before
  /// the main loop takes them from its ring; writing one early could put it
  /// before a command the station applied first.) Until the first call,
  /// every event counts as applied.
  void release_until(int64_t t_ns);
  /// Writes the commands and the released raw events, in time order; syncs
  /// when due. An error stops the recording (what was written stays readable).
  Status flush();
  /// Raw events kept: in flight, or released and waiting for a flush.
  size_t raw_kept() {
    std::lock_guard lock(raw_mutex_);
    return raw_.size();
  }
  /// Flushes and closes; returns the records written. The events not yet
  /// released stay for a next recording.
  Result<int64_t> stop();

 private:
  // Takes the raw events up to released_t_ns_ out, into `into` (null: lets
  // them go; the sculpting thread does so each poll, without allocating).
  void take_released(std::vector<hal::RawEvent>* into);
  std::optional<sim::SessionWriter> writer_;
  std::filesystem::path path_;
  std::vector<sim::SessionRecord> pending_;  // main thread's commands
  std::mutex raw_mutex_;
  // From the reader thread: while nothing records, only the events in
  // flight (tapped, not yet released), a poll's worth; a device read while
  // nothing records does not pile its events up here.
  std::vector<hal::RawEvent> raw_;
  int64_t last_t_ns_ = 0;
  int64_t released_t_ns_ = std::numeric_limits<int64_t>::max();
};

}  // namespace sculpt::station
