#include "sculpt/hal/haptics/haptic_loop.h"

#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "sculpt/hal/force/sim_arm.h"

namespace sculpt::hal {
namespace {

constexpr int64_t kMs = 1'000'000;

// A device at the byte edge's level of detail the loop cares about: it plays
// scripted readings and keeps every force written and every zero().
class ScriptedDevice final : public ForceDevice {
 public:
  std::vector<ForceIo> reads;  // per tick; past the end: kOk
  std::vector<glm::vec3> written;
  int zeroes = 0;
  ForceDeviceState state;

  const DeviceInfo& info() const override { return info_; }
  const ForceLimits& limits() const override { return sim_arm_limits(); }
  ForceIo read(ForceDeviceState& out) override {
    const size_t tick = reads_done_++;
    out = state;
    return tick < reads.size() ? reads[tick] : ForceIo::kOk;
  }
  ForceIo write(glm::vec3 force_n) override {
    written.push_back(force_n);
    return ForceIo::kOk;
  }
  void zero() noexcept override { ++zeroes; }

 private:
  DeviceInfo info_;
  size_t reads_done_ = 0;
};

// A wall at y = 0 (device frame, mm): a spring into it.
class Wall final : public ForceLaw {
 public:
  explicit Wall(float stiffness_n_per_mm) : k_(stiffness_n_per_mm) {}
  glm::vec3 force_n(const HapticInput& in) override {
    ++calls;
    const float depth = -in.device.position_mm.y;
    return glm::vec3(0.0f, depth > 0.0f ? k_ * depth : 0.0f, 0.0f);
  }
  int calls = 0;

 private:
  float k_;
};

class Thrower final : public ForceLaw {
 public:
  glm::vec3 force_n(const HapticInput&) override { throw std::runtime_error("bug"); }
};

HapticLoopOptions no_ramp() {
  HapticLoopOptions o;
  o.safety.ramp_s = 0.0;
  return o;
}

TEST(HapticLoop, ForceIsWrittenOnlyOnceEnabledAndRampsIn) {
  ScriptedDevice device;
  device.state.position_mm = {0.0f, -1.0f, 0.0f};
  Wall wall(2.0f);
  HapticLoop loop(device, wall);
  int64_t t = 0;
  for (; t < 5 * kMs; t += kMs)
    ASSERT_TRUE(loop.tick(t));
  for (const glm::vec3& f : device.written)
    EXPECT_EQ(f, glm::vec3(0.0f));
  loop.enable();
  for (; t < 1000 * kMs; t += kMs)
    ASSERT_TRUE(loop.tick(t));
  EXPECT_NEAR(device.written[5 + 250].y, 1.0f, 0.01f);  // half way up the ramp
  EXPECT_FLOAT_EQ(device.written.back().y, 2.0f);
  EXPECT_EQ(loop.live().ticks.load(), 1000);
  EXPECT_EQ(loop.live().late_ticks.load(), 0);
  EXPECT_FLOAT_EQ(loop.live().max_force_n.load(), 2.0f);
  EXPECT_EQ(loop.periods().count(), 999);
}

TEST(HapticLoop, UnpluggedMidContactTheForceStopsOnThatTick) {
  SimArm arm([] {
    HandScript hand;
    hand.path.push_back({0.0, glm::vec3(0.0f, -5.0f, 0.0f)});  // pressing into the wall
    hand.unplug_s = 0.3;
    return hand;
  }());
  Wall wall(1.0f);
  HapticLoop loop(arm, wall, no_ramp());
  loop.enable();
  int64_t t = 0;
  while (loop.tick(t))
    t += kMs;
  EXPECT_EQ(loop.state(), HapticLoopState::kRemoved);
  EXPECT_EQ(t, 300 * kMs);
  EXPECT_EQ(loop.last().force_n, glm::vec3(0.0f));
  EXPECT_EQ(arm.motor_force_n(), glm::vec3(0.0f));
  EXPECT_FALSE(loop.tick(t + kMs));
  // The records end with the zero-force tick of the unplug, just after a
  // tick that pressed.
  std::vector<HapticTickRecord> records;
  HapticTickRecord record;
  while (loop.records().try_pop(record))
    records.push_back(record);
  ASSERT_EQ(records.size(), 301u);
  EXPECT_GT(records[299].force_n.y, 1.0f);
  EXPECT_EQ(records[300].t_ns, 300 * kMs);
  EXPECT_EQ(records[300].force_n, glm::vec3(0.0f));
}

TEST(HapticLoop, ALawThatThrowsGetsZeroForceUntilEnabledAgain) {
  ScriptedDevice device;
  Thrower thrower;
  HapticLoop loop(device, thrower, no_ramp());
  loop.enable();
  ASSERT_TRUE(loop.tick(0));
  EXPECT_EQ(loop.state(), HapticLoopState::kFaulted);
  EXPECT_EQ(device.written.back(), glm::vec3(0.0f));
  ASSERT_TRUE(loop.tick(kMs));
  EXPECT_EQ(device.written.back(), glm::vec3(0.0f));
}

TEST(HapticLoop, ADropButtonOrRequestZeroesTheForceOnTheNextTick) {
  ScriptedDevice device;
  device.state.position_mm = {0.0f, -2.0f, 0.0f};
  Wall wall(1.0f);
  HapticLoopOptions options = no_ramp();
  options.drop_buttons = 0x2;
  HapticLoop loop(device, wall, options);
  loop.enable();
  ASSERT_TRUE(loop.tick(0));
  EXPECT_FLOAT_EQ(device.written.back().y, 2.0f);
  device.state.buttons = 0x2;
  ASSERT_TRUE(loop.tick(kMs));
  EXPECT_EQ(device.written.back(), glm::vec3(0.0f));
  device.state.buttons = 0;
  ASSERT_TRUE(loop.tick(2 * kMs));
  EXPECT_EQ(device.written.back(), glm::vec3(0.0f));  // stays off
  loop.enable();
  ASSERT_TRUE(loop.tick(3 * kMs));
  EXPECT_FLOAT_EQ(device.written.back().y, 2.0f);
  loop.drop();
  ASSERT_TRUE(loop.tick(4 * kMs));
  EXPECT_EQ(device.written.back(), glm::vec3(0.0f));
}

TEST(HapticLoop, DeviceFaultsAndUnhomedDevicesGetZeroForceAndLateTicksAreCounted) {
  ScriptedDevice device;
  device.state.position_mm = {0.0f, -2.0f, 0.0f};
  device.reads = {ForceIo::kOk, ForceIo::kFault, ForceIo::kOk};
  Wall wall(1.0f);
  HapticLoop loop(device, wall, no_ramp());
  loop.enable();
  ASSERT_TRUE(loop.tick(0));
  ASSERT_TRUE(loop.tick(kMs));
  ASSERT_TRUE(loop.tick(2 * kMs));
  ASSERT_EQ(device.written.size(), 3u);
  EXPECT_FLOAT_EQ(device.written[0].y, 2.0f);
  EXPECT_EQ(device.written[1], glm::vec3(0.0f));
  EXPECT_FLOAT_EQ(device.written[2].y, 2.0f);
  EXPECT_EQ(loop.live().device_faults.load(), 1);
  // 2 ms apart is late; 4 ms apart trips the watchdog and writes zero.
  ASSERT_TRUE(loop.tick(4 * kMs));
  EXPECT_FLOAT_EQ(device.written.back().y, 2.0f);
  ASSERT_TRUE(loop.tick(8 * kMs));
  EXPECT_EQ(device.written.back(), glm::vec3(0.0f));
  EXPECT_EQ(loop.live().late_ticks.load(), 2);
  EXPECT_FLOAT_EQ(loop.live().worst_period_us.load(), 4000.0f);
  EXPECT_EQ(loop.safety().counters().watchdog_trips, 1);
  // A device that has not found its home gets no force and its law is not asked.
  const int calls = wall.calls;
  device.state.homed = false;
  ASSERT_TRUE(loop.tick(9 * kMs));
  EXPECT_EQ(device.written.back(), glm::vec3(0.0f));
  EXPECT_EQ(wall.calls, calls);
}

}  // namespace
}  // namespace sculpt::hal
