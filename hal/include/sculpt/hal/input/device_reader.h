#pragma once
// One reader thread per open device: the only code that touches its handle.
// It reads RawEvents, runs them through its DeviceStream (kConnected, the
// MotionPipeline's events, kDisconnected also when the device vanishes) and
// pushes the results into a lock-free SPSC ring; the main loop drains the
// ring with poll(), every event in the order the device sent it.
//
// Each event carries when its report was read (InputEvent::arrived_ns),
// and the reader rings ReaderOptions::doorbell once a report's events are
// in the ring.
//
// Counters: `dropped` motion samples that did not fit the ring (never a button
// or connect event: the thread waits for room for those); `late` samples
// read more than `late_after_ns` before they were polled.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <thread>
#include <vector>

#include "sculpt/base/doorbell.h"
#include "sculpt/hal/input/device_stream.h"
#include "sculpt/hal/input/motion_pipeline.h"
#include "sculpt/hal/input/spsc_ring.h"
#include "sculpt/hal/types/device.h"
#include "sculpt/hal/types/input_event.h"

namespace sculpt::hal {

struct ReaderOptions {
  size_t ring_capacity = 4096;         ///< events; 4 s of a 1 kHz device
  int read_timeout_ms = 20;            ///< how often the thread checks for stop()
  int64_t late_after_ns = 20'000'000;  ///< a sample read this long before it is polled is late
  /// Called on the reader thread with every raw event, the removal included,
  /// before it is parsed: the session recorder's tap. Must be quick and
  /// thread-safe; empty for none.
  std::function<void(const RawEvent&)> on_raw;
  /// The SCHED_FIFO priority the reader thread takes when the system grants
  /// it (sculpt/base/thread_priority.h), 0 for none. The window's readers
  /// run ahead of its sculpting and meshing: a report is then timed when it
  /// came, not when a busy core let its reader run.
  int realtime_priority = 0;
  /// Rung after each report's events are pushed, so the thread that polls
  /// the readers can sleep until one has something (InputHub::run()); null
  /// for none.
  std::shared_ptr<Doorbell> doorbell;
};

struct ReaderCounters {
  int64_t raw_events = 0;
  int64_t motion_samples = 0;
  int64_t dropped = 0;
  int64_t late = 0;
};

/// What one poll() gathered.
struct InputFrame {
  /// Every event, motion included, in the order the device sent them: what
  /// the station's loop consumes, so a button acts at the pose it was pressed
  /// at and a stroke follows the device's path sample by sample (a live
  /// session then sculpts exactly what its recording replays to).
  std::vector<InputEvent> events;
  void clear() { events.clear(); }
};

class DeviceReader {
 public:
  DeviceReader(uint32_t device_id, std::unique_ptr<Device> device, MotionPipeline pipeline,
               ReaderOptions options = {});
  ~DeviceReader();  ///< stops and joins the thread
  DeviceReader(const DeviceReader&) = delete;
  DeviceReader& operator=(const DeviceReader&) = delete;

  void start();
  /// Asks the thread to finish and joins it (it pushes kDisconnected).
  void stop();

  /// Main thread: moves what arrived into `frame` (appending). `now_ns` is the
  /// time used for the late count.
  void poll(InputFrame& frame, int64_t now_ns);

  /// True once the thread has pushed kDisconnected and poll() has taken it.
  bool finished() const { return finished_; }
  uint32_t device_id() const { return device_id_; }
  const DeviceInfo& info() const { return info_; }
  ReaderCounters counters() const;

 private:
  void run();
  void push_blocking(const InputEvent& e);

  uint32_t device_id_;
  DeviceInfo info_;
  std::unique_ptr<Device> device_;  // touched only by the thread once started
  DeviceStream stream_;             // touched only by the thread once started
  ReaderOptions options_;
  SpscRing<InputEvent> ring_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<int64_t> raw_events_{0};
  std::atomic<int64_t> motion_samples_{0};
  std::atomic<int64_t> dropped_{0};
  int64_t late_ = 0;       // main thread only
  bool finished_ = false;  // main thread only
};

}  // namespace sculpt::hal
