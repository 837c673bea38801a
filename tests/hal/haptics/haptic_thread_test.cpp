#include "sculpt/hal/haptics/haptic_thread.h"

#include <sched.h>

#include <atomic>
#include <thread>

#include <gtest/gtest.h>

#include "sculpt/hal/types/clock.h"

namespace sculpt::hal {
namespace {

class CountingDevice final : public ForceDevice {
 public:
  std::atomic<int> reads{0}, zeroes{0};
  int remove_after = -1;  // reads; -1: never

  const DeviceInfo& info() const override { return info_; }
  const ForceLimits& limits() const override { return sim_arm_limits(); }
  ForceIo read(ForceDeviceState& out) override {
    out = {};
    const int n = ++reads;
    return remove_after >= 0 && n > remove_after ? ForceIo::kRemoved : ForceIo::kOk;
  }
  ForceIo write(glm::vec3) override { return ForceIo::kOk; }
  void zero() noexcept override { ++zeroes; }

 private:
  DeviceInfo info_;
};

class NoForce final : public ForceLaw {
 public:
  glm::vec3 force_n(const HapticInput&) override { return glm::vec3(0.0f); }
};

TEST(HapticThread, TicksUntilStoppedThenLeavesTheDeviceWithZeroForce) {
  CountingDevice device;
  NoForce law;
  HapticLoop loop(device, law);
  HapticThread thread(loop, device);
  thread.start();
  // Either real-time or one line saying why not.
  EXPECT_TRUE(thread.realtime() ||
              thread.realtime_note().find("no real-time priority") != std::string::npos);
  while (loop.live().ticks.load() < 20)
    std::this_thread::yield();
  EXPECT_TRUE(thread.running());
  thread.stop();
  EXPECT_FALSE(thread.running());
  EXPECT_GE(device.zeroes.load(), 1);
  const int64_t ticks = loop.live().ticks.load();
  EXPECT_GE(ticks, 20);
  // Ticks are not bunched up to catch up: each period is one deadline or more,
  // so the ticks never outnumber the deadlines passed.
  EXPECT_EQ(loop.periods().count(), ticks - 1);
}

// Waking early and polling never runs a tick before its deadline: however
// the machine is loaded, the ticks never outnumber the deadlines passed.
TEST(HapticThread, PollingToTheDeadlineNeverTicksEarly) {
  CountingDevice device;
  NoForce law;
  HapticLoop loop(device, law);
  HapticThreadOptions options;
  options.spin_ns = 300'000;
  HapticThread thread(loop, device, options);
  const int64_t start_ns = monotonic_ns();
  thread.start();
  while (loop.live().ticks.load() < 30)
    std::this_thread::yield();
  thread.stop();
  const int64_t elapsed_ns = monotonic_ns() - start_ns;
  const int64_t ticks = loop.live().ticks.load();
  EXPECT_GE(ticks, 30);
  EXPECT_LE(ticks, elapsed_ns / options.period_ns + 1);
  EXPECT_GE(device.zeroes.load(), 1);
}

// The device's own state, not atomic: the standby twin and the first thread
// must never tick at once (ThreadSanitizer checks this in CI), and a deadline
// is ticked once whichever thread wakes for it.
class PlainCountingDevice final : public ForceDevice {
 public:
  int64_t reads = 0;

  const DeviceInfo& info() const override { return info_; }
  const ForceLimits& limits() const override { return sim_arm_limits(); }
  ForceIo read(ForceDeviceState& out) override {
    out = {};
    ++reads;
    return ForceIo::kOk;
  }
  ForceIo write(glm::vec3) override { return ForceIo::kOk; }
  void zero() noexcept override {}

 private:
  DeviceInfo info_;
};

TEST(HapticThread, TheStandbyTwinNeverTicksAtOnceWithTheFirstNorTwiceForADeadline) {
  PlainCountingDevice device;
  NoForce law;
  HapticLoop loop(device, law);
  HapticThread thread(loop, device);
  const int64_t start_ns = monotonic_ns();
  thread.start();
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  ASSERT_EQ(sched_getaffinity(0, sizeof allowed, &allowed), 0);
  EXPECT_EQ(thread.threads(), CPU_COUNT(&allowed) >= 2 ? 2 : 1);
  while (loop.live().ticks.load() < 200)
    std::this_thread::yield();
  thread.stop();
  const int64_t elapsed_ns = monotonic_ns() - start_ns;
  EXPECT_EQ(device.reads, loop.live().ticks.load());
  EXPECT_LE(device.reads, elapsed_ns / HapticThreadOptions{}.period_ns + 1);
}

TEST(HapticThread, WithoutTheStandbyOneThreadTicks) {
  PlainCountingDevice device;
  NoForce law;
  HapticLoop loop(device, law);
  HapticThreadOptions options;
  options.standby = false;
  HapticThread thread(loop, device, options);
  thread.start();
  EXPECT_EQ(thread.threads(), 1);
  while (loop.live().ticks.load() < 20)
    std::this_thread::yield();
  thread.stop();
  EXPECT_EQ(thread.standby_rescues(), 0);
}

TEST(HapticThread, EndsByItselfWhenTheDeviceGoesAway) {
  CountingDevice device;
  device.remove_after = 5;
  NoForce law;
  HapticLoop loop(device, law);
  HapticThread thread(loop, device);
  thread.start();
  while (thread.running())
    std::this_thread::yield();
  EXPECT_EQ(loop.state(), HapticLoopState::kRemoved);
  EXPECT_EQ(loop.live().ticks.load(), 5);
  EXPECT_GE(device.zeroes.load(), 1);
}

}  // namespace
}  // namespace sculpt::hal
