#pragma once
// Records what the station does into a session file while it runs: the raw
// reports of the device (handed over from its reader thread) and every
// station command (from the UI), merged in time order. The file is appended
// as it goes and synced at least every 0.25 s, so a crash loses at most that.
//
// Thread safety: raw() may be called from any thread (the reader's raw tap);
// everything else from the main loop.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "sculpt/core/util/result.h"
#include "sculpt/sim/session/session_file.h"

namespace sculpt::station {

class SessionRecorder {
 public:
  /// Starts a recording in `path` (replacing it) whose first records are
  /// `opening` (the commands that rebuild the station's current settings).
  core::Status start(const std::filesystem::path& path, const sim::SessionHeader& header,
                     const std::vector<sim::Command>& opening, int64_t now_ns);
  bool recording() const { return writer_.has_value(); }
  const std::filesystem::path& path() const { return path_; }

  /// A station command, at `t_ns` (monotonic).
  void command(const sim::Command& command, int64_t t_ns);
  /// A raw device event (any thread).
  void raw(const hal::RawEvent& event);
  /// Writes what arrived, in time order; syncs when due. An error stops the
  /// recording (what was written stays readable).
  core::Status flush();
  /// Flushes and closes; returns the records written.
  core::Result<int64_t> stop();

 private:
  std::optional<sim::SessionWriter> writer_;
  std::filesystem::path path_;
  std::vector<sim::SessionRecord> pending_;  // main thread's commands
  std::mutex raw_mutex_;
  std::vector<hal::RawEvent> raw_;  // from the reader thread
  int64_t last_t_ns_ = 0;
};

}  // namespace sculpt::station
