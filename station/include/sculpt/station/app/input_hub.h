#pragma once
// The station's sculpting thread: it reads the devices and sculpts what they
// say as their reports arrive (their readers wake it, and it polls at least
// once a millisecond), instead of once a frame behind a draw that takes
// 15-30 ms on a software renderer.
//
//   device readers --rings--> InputHub thread: poll (as a reader rings its
//                             doorbell, else once a millisecond), order device
//                             samples and the session's commands,
//                             StationController sculpts, SurfaceMesher::submit()
//   render thread: pointer, keys, panel (under mutex()), then draws unlocked
//
// The controller and the volume it owns are used by this thread and, under
// mutex(), by the render thread for what the user does with the mouse, the
// keys and the panel (a few hundred microseconds a frame). Drawing, which is
// most of a frame, never holds it, so sculpting waits at most for the
// panel, and the frame at most for one dab. Sculpting stays on one thread in
// the order the samples came, so a live session ends on its replay's volume.
//
// GL-free: tested without a window (tests/station/app/input_hub_test.cpp).

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "sculpt/base/priority_inheriting_mutex.h"
#include "sculpt/hal/registry/device_registry.h"
#include "sculpt/sim/replay/sim_backend.h"
#include "sculpt/sim/session/session.h"
#include "sculpt/station/app/station_controller.h"
#include "sculpt/station/view/surface_mesher.h"

namespace sculpt::station {

/// Work that joins the sculpting thread at every poll, after the devices
/// are read: a force device's sculpting side (haptics/haptic_station.h).
class PollListener {
 public:
  virtual ~PollListener() = default;
  /// On the sculpting thread, under mutex().
  virtual void on_poll(StationController& controller, int64_t now_ns) = 0;
};

struct InputHubFigures {
  int64_t polls = 0;  ///< times the devices were read
  /// Of them, those a reader's ring woke early (a report came between
  /// the clock's polls).
  int64_t polls_on_reports = 0;
  double sculpt_ms = 0;  ///< time spent sculpting what they said, summed
  /// The sculpting thread's waits for the render thread's turn.
  struct TurnWaits {
    double sum_ms = 0;
    double max_ms = 0;
    int64_t over_1ms = 0;  ///< polls that waited longer than a millisecond
  } waits;
  /// Device events held while an offset or closing computed in the
  /// background (sculpted once it landed, in their order).
  int64_t held_events = 0;
  /// The sculpting thread's page faults since it began polling (its heap
  /// warmed before): about 8 us each on the machines measured, so a dab
  /// that touches fresh memory waits for it. None while the reserve lasts.
  int64_t page_faults = 0;
};

class InputHub {
 public:
  static constexpr int64_t kPollIntervalNs = 1'000'000;  ///< 1 kHz
  /// Polls a reader's reports wake come at least this far apart (4 kHz).
  static constexpr int64_t kMinPollSpacingNs = 250'000;
  static constexpr int64_t kScanIntervalNs = 1'000'000'000;  ///< hot-plug, each second
  /// Recording flushes and autosave checks (StationController::tick).
  static constexpr int64_t kTickIntervalNs = 16'000'000;
  /// Device events held while an offset or closing computes, at most (a
  /// minute of a 1 kHz device, about 4 MB); then the hub waits for it.
  static constexpr size_t kMaxHeldEvents = 60'000;

  /// `sim` is the registry's sim backend when a session plays as a device
  /// (else null); `normalizer_text` the settings its devices read with
  /// (the panel shows them). Nothing runs until start().
  InputHub(StationController& controller, std::unique_ptr<hal::DeviceRegistry> registry,
           sim::SimBackend* sim, std::string normalizer_text, SurfaceMesher& mesher);
  ~InputHub();
  InputHub(const InputHub&) = delete;
  InputHub& operator=(const InputHub&) = delete;

  /// Starts the sculpting thread without letting it poll: it touches
  /// `warm_heap_bytes` of its heap (warm_this_threads_heap(): worth it only
  /// once freed memory is kept, keep_freed_memory()), when that is not 0
  /// fills its pool of stroke buffers (core::keep_stroke_buffers()), and
  /// waits for start().
  /// Returns once the heap is warm: tens of milliseconds that must pass
  /// before the devices and a force device's loop start, not after.
  void prepare(size_t warm_heap_bytes);
  /// Lets the sculpting thread poll (starting it first, unwarmed, when
  /// prepare() was not called).
  void start();
  /// Stops the thread; what it read is sculpted. Safe to call twice.
  void stop();

  /// Held to use the controller, or the volume, from another thread. Its
  /// holder runs at the real-time sculpting thread's priority while that
  /// waits for it (priority_inheriting_mutex.h).
  PriorityInheritingMutex& mutex() { return mutex_; }
  /// mutex() for a frame: waited for when `must` (the last frame, a
  /// picture), else given up after a millisecond, so a frame is never held
  /// by a long poll (a big tool's first placement holds it tens of
  /// milliseconds; an ordinary poll a fraction of one). Check owns_lock().
  std::unique_lock<PriorityInheritingMutex> frame_turn(bool must);
  /// Under mutex(): the level to mesh each brick at (the camera's choice).
  void set_levels(std::vector<int> levels) { levels_ = std::move(levels); }
  /// Under mutex(): reads the devices and hands the volume's changes to
  /// the mesher now, not at the next poll (a picture of a given frame,
  /// tests, and before start()).
  /// `land`: an offset or closing still computing is waited for and landed
  /// first (the last poll, at the window's end: nothing is left unapplied).
  void poll_now(bool land = false);
  /// Joins every poll, after the devices; set before start(). Null: none.
  void set_listener(PollListener* listener) { listener_ = listener; }
  /// The sim device's session has played (or its device went).
  bool replay_done() const { return replay_done_.load(std::memory_order_acquire); }
  /// Under mutex().
  const InputHubFigures& figures() const { return figures_; }

 private:
  void run();
  void poll(int64_t now_ns, bool land = false);  // mutex_ held
  // Sculpts the input held while an offset or closing computed, once it has
  // landed (mutex_ held): before the next poll's, or before a command from
  // the render thread (the controller's input barrier, which lands it
  // first), so every input is taken in the order it came, as the recording
  // replays it.
  void release_held(int64_t now_ns);
  void note_devices();

  StationController& controller_;
  std::unique_ptr<hal::DeviceRegistry> registry_;
  sim::SimBackend* sim_;
  const std::string normalizer_text_;
  SurfaceMesher& mesher_;
  PollListener* listener_ = nullptr;

  PriorityInheritingMutex mutex_;
  // Under mutex_.
  std::vector<int> levels_;
  hal::InputFrame input_;
  std::vector<std::pair<int64_t, sim::Command>> pending_commands_;
  // Reports and commands held while an offset or closing computes.
  std::vector<hal::InputEvent> held_events_;
  std::vector<std::pair<int64_t, sim::Command>> held_commands_;
  int64_t newest_report_t_ns_;
  int64_t last_scan_ns_ = 0;
  // Whether the session played as a device has been started (run()).
  bool session_started_ = false;
  static constexpr int64_t kSessionStartWaitNs = 2'000'000'000;
  int64_t last_tick_ns_ = 0;
  uint32_t device_id_ = 0;  // the device the panel reports on
  InputHubFigures figures_;

  std::atomic<bool> replay_done_{false};
  std::atomic<bool> stop_{false};
  // prepare() -> start(): the thread waits on `go_` (under gate_).
  std::mutex gate_;
  std::condition_variable gate_changed_;
  bool warmed_ = false;
  bool go_ = false;
  std::thread thread_;
};

}  // namespace sculpt::station
