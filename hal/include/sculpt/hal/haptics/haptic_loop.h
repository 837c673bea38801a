#pragma once
// One force device's haptic loop, tick by tick (DESIGN.md §5a). Each tick:
// read the device, ask the force law for a force, pass it through the safety
// rules (force/force_safety.h), write it, and publish what happened. Time is
// passed in, so the same ticks run in real time (HapticThread, ~1 kHz) and in
// virtual time (replays, tests, the simulated arm), giving the same forces.
//
// The law is the station's: hal knows no material. It runs on the loop's
// thread and must not wait for anything (DESIGN.md §5a: read the patch the
// sculpting side publishes, never lock).
//
// Thread safety: tick() from one thread (the loop's). enable(), drop() and
// live() from any thread: requests are atomic and take effect on the next tick.

#include <atomic>
#include <cstdint>

#include <glm/vec3.hpp>

#include "sculpt/base/latency_histogram.h"
#include "sculpt/hal/force/force_device.h"
#include "sculpt/hal/force/force_safety.h"
#include "sculpt/hal/input/spsc_ring.h"

namespace sculpt::hal {

/// What the law sees each tick.
struct HapticInput {
  int64_t t_ns = 0;
  ForceDeviceState device;
};

/// Computes the force for a tick. Implementations must not block or throw on
/// purpose; an exception still drops the force and stops the law being asked.
class ForceLaw {
 public:
  virtual ~ForceLaw() = default;
  /// The force on the hand, N, device frame.
  virtual glm::vec3 force_n(const HapticInput& input) = 0;
  /// What the last force_n() read besides the device (the station's law:
  /// which patch and whether the clutch key was held), opaque to the loop:
  /// a recording keeps it so a replay can give a law the same inputs.
  virtual uint64_t inputs() const { return 0; }
};

/// A request to the loop from another thread, taken at the next tick.
enum class HapticRequest : uint8_t { kNone, kEnable, kDrop };

/// One tick as it happened: what a recording keeps and the station draws.
struct HapticTickRecord {
  int64_t t_ns = 0;
  glm::vec3 position_mm{0.0f};
  uint32_t buttons = 0;
  /// The force written (after the safety rules), N.
  glm::vec3 force_n{0.0f};
  /// What a replay needs to run the tick again (sessions keep it): the
  /// tick's number in its loop (a gap shows records were lost), what the
  /// read said, the request the tick took, and the law's inputs() when the
  /// law was asked (0 when not).
  uint32_t index = 0;
  ForceIo read = ForceIo::kOk;
  bool homed = true;
  HapticRequest request = HapticRequest::kNone;
  uint64_t law_inputs = 0;
};

enum class HapticLoopState : uint8_t {
  kRunning,
  kRemoved,  ///< the device went away; the loop has stopped
  kFaulted,  ///< the law threw; force is off until enable()
};

struct HapticLoopOptions {
  ForceSafetyOptions safety;
  /// A period above this counts as a late tick, ns.
  int64_t late_period_ns = 1'500'000;
  /// Device buttons (bit mask) that drop the force while pressed.
  uint32_t drop_buttons = 0;
  /// Tick records kept for the consumer (the sculpting side, a recording).
  size_t record_capacity = 4096;
};

/// Counters a panel reads while the loop runs (relaxed atomics: each is
/// exact, a set of them may be a tick apart).
struct HapticLiveCounters {
  std::atomic<int64_t> ticks{0};
  std::atomic<int64_t> late_ticks{0};
  std::atomic<int64_t> device_faults{0};
  std::atomic<int64_t> records_dropped{0};
  std::atomic<float> worst_period_us{0.0f};
  std::atomic<float> max_force_n{0.0f};
  std::atomic<float> ramp{0.0f};
};

class HapticLoop {
 public:
  HapticLoop(ForceDevice& device, ForceLaw& law, const HapticLoopOptions& options = {});

  /// Runs one tick at t_ns (increasing). False once the loop has stopped for
  /// good (the device was removed): call no more.
  bool tick(int64_t t_ns);

  /// Requests force on (it ramps in) / off at once, from any thread; the
  /// last request before a tick wins.
  void enable() { request_.store(HapticRequest::kEnable, std::memory_order_release); }
  void drop() { request_.store(HapticRequest::kDrop, std::memory_order_release); }

  /// Any thread.
  HapticLoopState state() const { return state_.load(std::memory_order_acquire); }
  const HapticTickRecord& last() const { return last_; }
  /// The loop's tick records, oldest first; the consumer pops them.
  SpscRing<HapticTickRecord>& records() { return records_; }
  const HapticLiveCounters& live() const { return live_; }
  /// Periods between ticks, us (the loop's thread, or after it stopped).
  const LatencyHistogram& periods() const { return periods_; }
  const ForceSafety& safety() const { return safety_; }

 private:
  // The request taken, if any.
  HapticRequest take_request();
  // Pushes last_ to records_, counting it when the consumer is behind.
  void publish();

  ForceDevice& device_;
  ForceLaw& law_;
  HapticLoopOptions options_;
  ForceSafety safety_;
  std::atomic<HapticLoopState> state_{HapticLoopState::kRunning};
  HapticTickRecord last_;
  bool have_last_tick_ = false;
  int64_t last_tick_ns_ = 0;
  SpscRing<HapticTickRecord> records_;
  HapticLiveCounters live_;
  LatencyHistogram periods_;
  std::atomic<HapticRequest> request_{HapticRequest::kNone};
  uint32_t ticks_ = 0;
};

}  // namespace sculpt::hal
