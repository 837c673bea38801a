#include "sculpt/hal/input/device_reader.h"

#include <chrono>
#include <thread>

#include "sculpt/base/thread_priority.h"
#include "sculpt/base/thread_times.h"
#include "sculpt/hal/types/clock.h"

namespace sculpt::hal {

DeviceReader::DeviceReader(uint32_t device_id, std::unique_ptr<Device> device,
                           MotionPipeline pipeline, ReaderOptions options)
    : device_id_(device_id),
      info_(device->info()),
      device_(std::move(device)),
      stream_(device_id, std::move(pipeline)),
      options_(options),
      ring_(options.ring_capacity) {}

DeviceReader::~DeviceReader() {
  stop();
}

void DeviceReader::start() {
  if (thread_.joinable()) return;
  thread_ = std::thread([this] {
    name_this_thread("reader");
    if (options_.realtime_priority > 0) {
      const int self[] = {this_thread_id()};
      (void)make_threads_realtime(self, options_.realtime_priority);  // else ordinary
    }
    run();
  });
}

void DeviceReader::stop() {
  stop_.store(true, std::memory_order_relaxed);
  if (thread_.joinable()) {
    thread_.join();
    // Its kDisconnected may not have fitted the ring; the reader is done either way.
    finished_ = true;
  }
}

void DeviceReader::push_blocking(const InputEvent& e) {
  // Events that must not be lost wait for room; the sculpting thread
  // drains the ring at each poll, so the wait is short. It sleeps rather
  // than yields: a real-time reader (the window makes it one) that yields
  // gives its core to no thread of lower priority, the sculpting thread
  // that would make the room included. stop() ends it so shutdown never
  // hangs.
  while (!ring_.try_push(e)) {
    if (stop_.load(std::memory_order_relaxed)) return;
    std::this_thread::sleep_for(std::chrono::microseconds(100));
  }
}

void DeviceReader::run() {
  std::vector<InputEvent> out;
  out.reserve(16);
  // Each event says when its report was read, and the poller hears of it.
  auto arrived = [&](int64_t read_ns) {
    for (InputEvent& e : out)
      e.arrived_ns = read_ns;
  };
  auto ring = [&] {
    if (options_.doorbell) options_.doorbell->ring();
  };
  const int64_t connected_ns = monotonic_ns();
  stream_.connect(connected_ns, out);
  arrived(connected_ns);
  push_blocking(out.front());
  ring();
  RawEvent raw;
  bool removed = false;
  int64_t last_t_ns = out.front().t_ns;
  while (!removed && !stop_.load(std::memory_order_relaxed)) {
    const ReadResult r = device_->read(raw, options_.read_timeout_ms);
    if (r == ReadResult::kTimeout) continue;
    const int64_t read_ns = monotonic_ns();
    if (options_.on_raw) options_.on_raw(raw);
    removed = r == ReadResult::kRemoved;
    if (removed) break;  // kDisconnected goes last, after the handle is released
    raw_events_.fetch_add(1, std::memory_order_relaxed);
    last_t_ns = raw.t_ns;
    out.clear();
    stream_.feed(raw, out);
    arrived(read_ns);
    for (const InputEvent& e : out) {
      if (e.kind == InputKind::kMotion) {
        motion_samples_.fetch_add(1, std::memory_order_relaxed);
        // Motion is state: when the ring is full the newest sample still
        // reaches the main loop later; this one is counted and let go.
        if (!ring_.try_push(e)) dropped_.fetch_add(1, std::memory_order_relaxed);
      } else {
        push_blocking(e);
      }
    }
    if (!out.empty()) ring();
  }
  const int64_t gone_ns = monotonic_ns();
  // Release the handle on this thread: it is the only one that touches it.
  device_.reset();
  out.clear();
  if (removed) {
    stream_.feed(raw, out);  // kDisconnected at the transport's time
  } else {
    stream_.disconnect(last_t_ns, out);
  }
  arrived(gone_ns);
  // When stopping, the main thread is joining us and not draining: one try.
  if (stop_.load(std::memory_order_relaxed)) {
    ring_.try_push(out.front());
  } else {
    push_blocking(out.front());
  }
  ring();
}

void DeviceReader::poll(InputFrame& frame, int64_t now_ns) {
  InputEvent e;
  while (ring_.try_pop(e)) {
    frame.events.push_back(e);
    if (e.kind == InputKind::kMotion && e.arrived_ns + options_.late_after_ns < now_ns) ++late_;
    if (e.kind == InputKind::kDisconnected) finished_ = true;
  }
}

ReaderCounters DeviceReader::counters() const {
  ReaderCounters c;
  c.raw_events = raw_events_.load(std::memory_order_relaxed);
  c.motion_samples = motion_samples_.load(std::memory_order_relaxed);
  c.dropped = dropped_.load(std::memory_order_relaxed);
  c.late = late_;
  return c;
}

}  // namespace sculpt::hal
