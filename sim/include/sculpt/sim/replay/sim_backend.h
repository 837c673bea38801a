#pragma once
// The "sim" backend: a recorded session played as a live device. It lists one
// device (the session's, backend "sim", path = the session file) whose reads
// return the recorded raw events at their recorded spacing (scaled by the
// speed), so `sculpt run --device sim:FILE` drives the same reader thread,
// ring, parsers and normaliser as a real device. The session's station
// commands are handed to the station through take_commands(). A recorded
// unplug is one: the handle reports it removed, the backend lists the device
// again (changed()), and the handle opened next plays on from the record
// after it, as a device plugged back in would (and as `sculpt replay` does:
// a fresh parser and normaliser, the same session).
//
// Deterministic replay does not go through this backend's thread: `sculpt
// replay` steps the records synchronously (SessionPlayer), which is what makes
// it bit-exact at any speed.

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "sculpt/hal/types/device.h"
#include "sculpt/sim/session/session.h"

namespace sculpt::sim {

class SimBackend final : public hal::Backend {
 public:
  /// Plays `session` (read from `path`) at `speed`; with `loop`, over and
  /// over (each round's times follow the last's a second after its end, so
  /// time keeps increasing): the soak test's endless sculptor.
  /// With `wait_for_start`, the device hands out nothing, and the session's
  /// clock does not run, until start_playing().
  SimBackend(Session session, std::string path, double speed = 1.0, bool loop = false,
             bool wait_for_start = false);
  std::string_view name() const override { return "sim"; }
  hal::BackendStatus status() override { return {}; }
  Result<std::vector<hal::DeviceInfo>> enumerate() override;
  Result<std::unique_ptr<hal::Device>> open(const hal::DeviceInfo& info) override;
  bool changed() override;

  /// Whether the device has handed out every record of the session (its
  /// reader has pushed them all by the time this is true). Thread-safe.
  bool played() const;
  /// Station commands whose time has come (thread-safe), in order.
  std::vector<std::pair<int64_t, Command>> take_commands();
  /// Starts the session's clock of a backend made to wait for it: its first
  /// record is due now, the rest at their recorded spacing. The window's
  /// sculpting thread calls it once the opening surface is meshed
  /// (InputHub::run()): a device opened while the window was still starting
  /// had handed its first 50 ms of reports out at once, and the demo's first
  /// ball came in one poll with the new block and the tool change
  /// (docs/performance.md). Thread-safe; once.
  void start_playing();

  struct Shared;

 private:
  std::shared_ptr<Shared> shared_;
  hal::DeviceInfo info_;
  bool changed_ = true;
};

}  // namespace sculpt::sim
