// EvdevForceDevice through the scripted fake (CI has no force-feedback
// device and no /dev/uinput): what open() asks of the device and in which
// order, the effect updated in place with the right level and direction,
// no update when nothing changed, clamping, position and buttons from the
// input events, unplug, faults, zero() and the destructor.
//
// Levels and directions are worked by hand with full scale 4 N:
// level = |F| / 4 N * 0x7fff rounded; direction = atan2(x, y) as a
// fraction of 0x10000 (constant_effect_mapping.h: 0x4000 pushes right,
// 0x0000 pushes away from the user).

#include "backends/evdev_ff/evdev_force_device.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "fake_evdev_io.h"

namespace sculpt::hal::evdev_ff {
namespace {

using testing::FakeEvdevIo;
using testing::FakeEvdevNode;
using testing::FakeEvdevSystem;
using testing::make_event;
using testing::Op;

constexpr const char* kNode = "/dev/input/event7";

input_absinfo range(int32_t value, int32_t minimum, int32_t maximum) {
  input_absinfo a{};
  a.value = value;
  a.minimum = minimum;
  a.maximum = maximum;
  return a;
}

// A two-axis stick with a 10-bit range, three buttons, constant force and gain.
FakeEvdevNode ff_stick() {
  FakeEvdevNode n;
  n.ev_types = {EV_SYN, EV_KEY, EV_ABS, EV_FF};
  n.ff = {FF_CONSTANT, FF_GAIN};
  n.abs = {ABS_X, ABS_Y};
  n.absinfo[ABS_X] = range(512, 0, 1023);
  n.absinfo[ABS_Y] = range(512, 0, 1023);
  n.keys = {BTN_TRIGGER, BTN_THUMB, BTN_THUMB2};
  n.id = {BUS_USB, 0x1234, 0x5678, 0x0100};
  n.name = "Test FF Stick";
  return n;
}

struct Rig {
  FakeEvdevSystem sys;
  Rig() {
    sys.nodes[kNode] = ff_stick();
    // Not 0, so a test can tell the kernel's id from a default.
    sys.next_effect_id = 5;
  }
  Result<std::unique_ptr<EvdevForceDevice>> open(const EvdevForceOptions& options = {}) {
    return EvdevForceDevice::open(std::make_unique<FakeEvdevIo>(sys), kNode, options);
  }
  std::unique_ptr<EvdevForceDevice> opened(const EvdevForceOptions& options = {}) {
    auto d = open(options);
    EXPECT_TRUE(d.ok()) << (d.ok() ? "" : d.error().message());
    return d.ok() ? std::move(d).value() : nullptr;
  }
  void queue(std::initializer_list<input_event> events) { sys.queue(kNode, events); }
  // The calls that act on the effect (uploads, removals, written events), in order.
  std::vector<testing::IoCall> effect_calls() const {
    std::vector<testing::IoCall> out;
    for (const auto& c : sys.calls) {
      if (c.op == Op::kUpload || c.op == Op::kRemove || c.op == Op::kWrite) out.push_back(c);
    }
    return out;
  }
  ForceDeviceState read(EvdevForceDevice& d, ForceIo expect = ForceIo::kOk) {
    ForceDeviceState s;
    EXPECT_EQ(d.read(s), expect);
    return s;
  }
};

ff_effect effect_of(const testing::IoCall& c) {
  ff_effect e{};
  std::memcpy(&e, c.bytes.data(), sizeof e);
  return e;
}

input_event event_of(const testing::IoCall& c) {
  input_event ev{};
  std::memcpy(&ev, c.bytes.data(), sizeof ev);
  return ev;
}

TEST(EvdevForceDevice, RefusesADeviceThatCannotPlayAConstantForce) {
  Rig rig;
  rig.sys.node(kNode).ff = {FF_RUMBLE, FF_PERIODIC, FF_GAIN};
  auto d = rig.open();
  ASSERT_FALSE(d.ok());
  EXPECT_NE(d.error().message().find(kNode), std::string::npos) << d.error().message();
  EXPECT_NE(d.error().message().find("FF_CONSTANT"), std::string::npos) << d.error().message();
  EXPECT_NE(d.error().message().find("rumble, periodic"), std::string::npos);
  EXPECT_TRUE(rig.effect_calls().empty()) << "nothing may be sent to a device refused";
  EXPECT_EQ(rig.sys.calls.back().op, Op::kClose);
}

TEST(EvdevForceDevice, RefusesADeviceWithoutForceFeedbackAtAll) {
  Rig rig;
  rig.sys.node(kNode).ev_types = {EV_SYN, EV_KEY, EV_ABS};
  auto d = rig.open();
  ASSERT_FALSE(d.ok());
  EXPECT_NE(d.error().message().find("no effects"), std::string::npos) << d.error().message();
}

TEST(EvdevForceDevice, OpensWithTheGainThenANewEffectThenPlaysIt) {
  Rig rig;
  auto d = rig.opened();
  ASSERT_TRUE(d);
  const auto calls = rig.effect_calls();
  ASSERT_EQ(calls.size(), 3u);

  ASSERT_EQ(calls[0].op, Op::kWrite);
  const input_event gain = event_of(calls[0]);
  EXPECT_EQ(gain.type, EV_FF);
  EXPECT_EQ(gain.code, FF_GAIN);
  EXPECT_EQ(gain.value, 0xffff);
  EXPECT_EQ(calls[0].bytes.size(), sizeof(input_event));

  ASSERT_EQ(calls[1].op, Op::kUpload);
  EXPECT_EQ(calls[1].request, static_cast<unsigned long>(EVIOCSFF));
  const ff_effect e = effect_of(calls[1]);
  EXPECT_EQ(e.type, FF_CONSTANT);
  EXPECT_EQ(e.id, -1) << "a new effect is asked for with id -1 (ff.rst)";
  EXPECT_EQ(e.u.constant.level, 0);
  EXPECT_EQ(e.replay.length, 0) << "0 = play until stopped";
  EXPECT_EQ(e.replay.delay, 0);

  ASSERT_EQ(calls[2].op, Op::kWrite);
  const input_event play = event_of(calls[2]);
  EXPECT_EQ(play.type, EV_FF);
  EXPECT_EQ(play.code, 5) << "play names the id the kernel gave";
  EXPECT_EQ(play.value, 1);

  EXPECT_EQ(d->effect_id(), 5);
  EXPECT_TRUE(d->playing());
}

TEST(EvdevForceDevice, SendsTheGainAskedForAndNoneToADeviceWithoutGain) {
  {
    Rig rig;
    EvdevForceOptions o;
    o.gain = 0x8000;
    auto d = rig.opened(o);
    ASSERT_TRUE(d);
    EXPECT_EQ(event_of(rig.effect_calls()[0]).value, 0x8000);
  }
  {
    Rig rig;
    rig.sys.node(kNode).ff = {FF_CONSTANT};
    auto d = rig.opened();
    ASSERT_TRUE(d);
    const auto calls = rig.effect_calls();
    ASSERT_EQ(calls.size(), 2u);
    EXPECT_EQ(calls[0].op, Op::kUpload);
  }
}

TEST(EvdevForceDevice, TurnsTheDevicesCentringSpringOff) {
  Rig rig;
  rig.sys.node(kNode).ff = {FF_CONSTANT, FF_GAIN, FF_AUTOCENTER};
  auto d = rig.opened();
  ASSERT_TRUE(d);
  const auto calls = rig.effect_calls();
  ASSERT_EQ(calls.size(), 4u);
  const input_event autocenter = event_of(calls[1]);
  EXPECT_EQ(autocenter.code, FF_AUTOCENTER);
  EXPECT_EQ(autocenter.value, 0);
  EXPECT_EQ(calls[2].op, Op::kUpload) << "before the effect, so it never fights the spring";
}

TEST(EvdevForceDevice, ReportsItsLimitsAsAnEffectBasedDevice) {
  Rig rig;
  EvdevForceOptions o;
  o.full_scale_n = 2.5f;
  o.workspace_half_range_mm = 30.0f;
  auto d = rig.opened(o);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->limits().capability, ForceCapability::kEffectBased);
  EXPECT_EQ(d->limits().max_force_n, 2.5f);
  EXPECT_EQ(d->limits().workspace_radius_mm, 30.0f);
  EXPECT_EQ(d->limits().name, "Test FF Stick");
  EXPECT_EQ(d->info().backend, "evdev-ff");
  EXPECT_EQ(d->info().path, kNode);
  EXPECT_EQ(d->info().vendor_product(), "1234:5678");
}

struct Push {
  glm::vec3 force_n;
  int16_t level;
  uint16_t direction;
};

class EvdevForceWrite : public ::testing::TestWithParam<Push> {};

TEST_P(EvdevForceWrite, UpdatesTheEffectInPlaceWithLevelAndDirection) {
  const Push p = GetParam();
  Rig rig;
  auto d = rig.opened();
  ASSERT_TRUE(d);
  const size_t before = rig.sys.uploads().size();
  EXPECT_EQ(d->write(p.force_n), ForceIo::kOk);
  const auto uploads = rig.sys.uploads();
  ASSERT_EQ(uploads.size(), before + 1);
  const ff_effect& e = uploads.back();
  EXPECT_EQ(e.id, 5) << "updated in place: the same id";
  EXPECT_EQ(e.type, FF_CONSTANT);
  EXPECT_EQ(e.u.constant.level, p.level);
  EXPECT_EQ(e.direction, p.direction);
  EXPECT_EQ(rig.sys.writes().size(), 2u) << "no second play: an update keeps the effect playing";
}

INSTANTIATE_TEST_SUITE_P(
    HandWorked, EvdevForceWrite,
    ::testing::Values(
        // 1 N of 4: 8191.75 -> 8192; pushes right: 0x4000.
        Push{{1.0f, 0.0f, 0.0f}, 8192, 0x4000},
        // 3 N left: 24575.25 -> 24575; 0xC000.
        Push{{-3.0f, 0.0f, 0.0f}, 24575, 0xC000},
        // 2 N away from the user: 16383.5 -> 16384; 0x0000.
        Push{{0.0f, 2.0f, 0.0f}, 16384, 0x0000},
        // 4 N toward the user, full scale: 0x7fff; 0x8000.
        Push{{0.0f, -4.0f, 0.0f}, 0x7fff, 0x8000},
        // 1 N right and 1 N away: |F| = 1.4142 -> 11584.88 -> 11585; an eighth of a turn.
        Push{{1.0f, 1.0f, 0.0f}, 11585, 0x2000},
        // 1 N right and 1 N toward the user: three eighths of a turn.
        Push{{1.0f, -1.0f, 0.0f}, 11585, 0x6000},
        // z does not reach a stick: the same as 1 N right.
        Push{{1.0f, 0.0f, 7.0f}, 8192, 0x4000}));

TEST(EvdevForceDevice, SendsNothingWhenTheEffectWouldNotChange) {
  Rig rig;
  auto d = rig.opened();
  ASSERT_TRUE(d);
  const size_t calls_at_open = rig.sys.calls.size();
  EXPECT_EQ(d->write(glm::vec3(0.0f)), ForceIo::kOk);
  EXPECT_EQ(rig.sys.calls.size(), calls_at_open) << "level 0 is what open() uploaded";

  EXPECT_EQ(d->write({1.0f, 0.0f, 0.0f}), ForceIo::kOk);
  EXPECT_EQ(d->write({1.0f, 0.0f, 0.0f}), ForceIo::kOk);
  // 1.00001 N is level 8192 too; a z change does not reach the stick.
  EXPECT_EQ(d->write({1.00001f, 0.0f, 3.0f}), ForceIo::kOk);
  EXPECT_EQ(rig.sys.uploads().size(), 2u);
  EXPECT_EQ(d->counters().effect_updates, 1);
}

TEST(EvdevForceDevice, AForceTooSmallForALevelKeepsTheLastDirection) {
  Rig rig;
  auto d = rig.opened();
  ASSERT_TRUE(d);
  ASSERT_EQ(d->write({-1.0f, 0.0f, 0.0f}), ForceIo::kOk);
  ASSERT_EQ(d->write({0.0f, 1e-6f, 0.0f}), ForceIo::kOk);
  const ff_effect last = rig.sys.uploads().back();
  EXPECT_EQ(last.u.constant.level, 0);
  EXPECT_EQ(last.direction, 0xC000) << "a level-0 update need not turn the effect";
}

TEST(EvdevForceDevice, ClampsToTheFullScaleKeepingTheDirection) {
  Rig rig;
  auto d = rig.opened();
  ASSERT_TRUE(d);
  // 10 N along (0.6, 0.8): clamped to 4 N, 0x7fff. atan2(0.6, 0.8) =
  // 0.643501 rad = 0.1024164 turn = 6711.96 -> 6712, as 1 N along it.
  ASSERT_EQ(d->write({6.0f, 8.0f, 0.0f}), ForceIo::kOk);
  const ff_effect clamped = rig.sys.uploads().back();
  EXPECT_EQ(clamped.u.constant.level, 0x7fff);
  EXPECT_EQ(clamped.direction, 6712);
  ASSERT_EQ(d->write({0.6f, 0.8f, 0.0f}), ForceIo::kOk);
  const ff_effect small = rig.sys.uploads().back();
  EXPECT_EQ(small.u.constant.level, 8192);
  EXPECT_EQ(small.direction, 6712);
}

TEST(EvdevForceDevice, ANonFiniteForceIsAFaultAndNoForce) {
  Rig rig;
  auto d = rig.opened();
  ASSERT_TRUE(d);
  ASSERT_EQ(d->write({2.0f, 0.0f, 0.0f}), ForceIo::kOk);
  EXPECT_EQ(d->write({std::nanf(""), 0.0f, 0.0f}), ForceIo::kFault);
  EXPECT_EQ(rig.sys.uploads().back().u.constant.level, 0);
}

TEST(EvdevForceDevice, ReportsTheStickInMillimetresByItsAxisRanges) {
  Rig rig;
  auto& node = rig.sys.node(kNode);
  node.abs = {ABS_X, ABS_Y, ABS_Z};
  node.absinfo[ABS_X] = range(0, 0, 1023);
  // A range not centred on zero: 0 is a quarter of the way, -0.5.
  node.absinfo[ABS_Z] = range(0, -100, 300);
  EvdevForceOptions o;
  o.workspace_half_range_mm = 40.0f;
  auto d = rig.opened(o);
  ASSERT_TRUE(d);

  // At open: the values the axes had (absinfo.value).
  ForceDeviceState s = rig.read(*d);
  EXPECT_FLOAT_EQ(s.position_mm.x, -40.0f);
  EXPECT_NEAR(s.position_mm.y, -40.0f * (2.0f * 512.0f / 1023.0f - 1.0f), 1e-4f);
  EXPECT_FLOAT_EQ(s.position_mm.z, -20.0f);
  EXPECT_TRUE(s.homed);

  // Right, pushed away (ABS_Y minimum = +y), z at its maximum.
  rig.queue({make_event(EV_ABS, ABS_X, 1023), make_event(EV_ABS, ABS_Y, 0),
             make_event(EV_ABS, ABS_Z, 300), make_event(EV_SYN, SYN_REPORT, 0)});
  s = rig.read(*d);
  EXPECT_FLOAT_EQ(s.position_mm.x, 40.0f);
  EXPECT_FLOAT_EQ(s.position_mm.y, 40.0f);
  EXPECT_FLOAT_EQ(s.position_mm.z, 40.0f);

  // z = 100 on -100..300 is the middle; beyond the range clamps (the input
  // core does not).
  rig.queue({make_event(EV_ABS, ABS_Z, 100), make_event(EV_ABS, ABS_X, 5000),
             make_event(EV_SYN, SYN_REPORT, 0)});
  s = rig.read(*d);
  EXPECT_FLOAT_EQ(s.position_mm.z, 0.0f);
  EXPECT_FLOAT_EQ(s.position_mm.x, 40.0f);
}

TEST(EvdevForceDevice, AppliesAFrameOnlyAtItsSynReport) {
  Rig rig;
  auto d = rig.opened();
  ASSERT_TRUE(d);
  rig.queue({make_event(EV_ABS, ABS_X, 1023)});
  ForceDeviceState s = rig.read(*d);
  EXPECT_NEAR(s.position_mm.x, 40.0f * (2.0f * 512.0f / 1023.0f - 1.0f), 1e-4f);
  rig.queue({make_event(EV_ABS, ABS_Y, 1023), make_event(EV_SYN, SYN_REPORT, 0)});
  s = rig.read(*d);
  EXPECT_FLOAT_EQ(s.position_mm.x, 40.0f);
  EXPECT_FLOAT_EQ(s.position_mm.y, -40.0f);
}

TEST(EvdevForceDevice, NumbersTheButtonsFromTheTrigger) {
  Rig rig;
  rig.sys.node(kNode).keys = {BTN_TRIGGER, BTN_THUMB, BTN_THUMB2, BTN_TRIGGER_HAPPY1, KEY_A};
  rig.sys.node(kNode).held = {BTN_THUMB};
  auto d = rig.opened();
  ASSERT_TRUE(d);
  EXPECT_EQ(rig.read(*d).buttons, 0b0010u) << "held at open (EVIOCGKEY)";

  rig.queue({make_event(EV_KEY, BTN_TRIGGER, 1), make_event(EV_KEY, BTN_THUMB2, 1),
             make_event(EV_KEY, BTN_TRIGGER_HAPPY1, 1), make_event(EV_KEY, KEY_A, 1),
             make_event(EV_SYN, SYN_REPORT, 0)});
  EXPECT_EQ(rig.read(*d).buttons, 0b1111u);
  // Autorepeat (2) is still held; 0 releases.
  rig.queue({make_event(EV_KEY, BTN_TRIGGER, 2), make_event(EV_KEY, BTN_THUMB, 0),
             make_event(EV_SYN, SYN_REPORT, 0)});
  EXPECT_EQ(rig.read(*d).buttons, 0b1101u);
}

TEST(EvdevForceDevice, NumbersAGamepadsButtonsFromSouth) {
  Rig rig;
  rig.sys.node(kNode).keys = {BTN_SOUTH, BTN_EAST, BTN_NORTH};
  auto d = rig.opened();
  ASSERT_TRUE(d);
  rig.queue({make_event(EV_KEY, BTN_SOUTH, 1), make_event(EV_KEY, BTN_NORTH, 1),
             make_event(EV_SYN, SYN_REPORT, 0)});
  EXPECT_EQ(rig.read(*d).buttons, 0b101u);
}

TEST(EvdevForceDevice, AfterAnOverrunReReadsTheStateInsteadOfTheBrokenFrame) {
  Rig rig;
  auto d = rig.opened();
  ASSERT_TRUE(d);
  auto& node = rig.sys.node(kNode);
  node.absinfo[ABS_X].value = 1023;  // where the stick really is now
  node.held = {BTN_THUMB};
  rig.queue({make_event(EV_ABS, ABS_X, 0), make_event(EV_SYN, SYN_DROPPED, 0),
             make_event(EV_ABS, ABS_X, 0), make_event(EV_KEY, BTN_TRIGGER, 1),
             make_event(EV_SYN, SYN_REPORT, 0)});
  const ForceDeviceState s = rig.read(*d);
  EXPECT_FLOAT_EQ(s.position_mm.x, 40.0f);
  EXPECT_EQ(s.buttons, 0b10u);
  EXPECT_EQ(d->counters().overruns, 1);
}

TEST(EvdevForceDevice, DropsBytesThatAreNoWholeEvent) {
  Rig rig;
  auto d = rig.opened();
  ASSERT_TRUE(d);
  const input_event ev = make_event(EV_ABS, ABS_X, 1023);
  const input_event syn = make_event(EV_SYN, SYN_REPORT, 0);
  std::vector<uint8_t> chunk = testing::bytes_of(&ev, sizeof ev);
  const auto b = testing::bytes_of(&syn, sizeof syn);
  chunk.insert(chunk.end(), b.begin(), b.end());
  chunk.insert(chunk.end(), {1, 2, 3});
  rig.sys.node(kNode).reads.push_back(chunk);
  EXPECT_FLOAT_EQ(rig.read(*d).position_mm.x, 40.0f);
  EXPECT_EQ(d->counters().stray_bytes, 3);
}

TEST(EvdevForceDevice, AnUnplugIsRemovedForGood) {
  Rig rig;
  auto d = rig.opened();
  ASSERT_TRUE(d);
  rig.sys.failures[Op::kRead] = {-ENODEV};
  rig.read(*d, ForceIo::kRemoved);
  const size_t calls = rig.sys.calls.size();
  rig.read(*d, ForceIo::kRemoved);
  EXPECT_EQ(d->write({1.0f, 0.0f, 0.0f}), ForceIo::kRemoved);
  d->zero();
  EXPECT_EQ(rig.sys.calls.size(), calls) << "a removed device is not asked again";
  d.reset();
  EXPECT_TRUE(rig.sys.calls_of(Op::kRemove).empty()) << "no EVIOCRMFF to a device that is gone";
  EXPECT_EQ(rig.sys.calls.back().op, Op::kClose);
}

TEST(EvdevForceDevice, AnUnplugSeenByTheUpdateIsRemovedToo) {
  Rig rig;
  auto d = rig.opened();
  ASSERT_TRUE(d);
  rig.sys.gone = true;
  EXPECT_EQ(d->write({1.0f, 0.0f, 0.0f}), ForceIo::kRemoved);
  rig.sys.gone = false;  // even if it came back, this handle is dead
  rig.read(*d, ForceIo::kRemoved);
}

TEST(EvdevForceDevice, OtherFailuresAreFaultsForThatCallOnly) {
  Rig rig;
  auto d = rig.opened();
  ASSERT_TRUE(d);
  rig.sys.failures[Op::kUpload] = {-EIO};
  EXPECT_EQ(d->write({1.0f, 0.0f, 0.0f}), ForceIo::kFault);
  EXPECT_EQ(d->effect().level, 0) << "the device still has the old level";
  EXPECT_EQ(d->write({1.0f, 0.0f, 0.0f}), ForceIo::kOk) << "tried again";
  EXPECT_EQ(d->effect().level, 8192);
  rig.sys.failures[Op::kRead] = {-EIO};
  rig.read(*d, ForceIo::kFault);
  rig.read(*d, ForceIo::kOk);
  EXPECT_EQ(d->counters().io_errors, 2);
}

TEST(EvdevForceDevice, ZeroSetsLevelZeroInPlaceThenStops) {
  Rig rig;
  auto d = rig.opened();
  ASSERT_TRUE(d);
  ASSERT_EQ(d->write({-2.0f, 0.0f, 0.0f}), ForceIo::kOk);
  const size_t before = rig.effect_calls().size();
  d->zero();
  const auto calls = rig.effect_calls();
  ASSERT_EQ(calls.size(), before + 2);
  ASSERT_EQ(calls[before].op, Op::kUpload);
  const ff_effect e = effect_of(calls[before]);
  EXPECT_EQ(e.id, 5);
  EXPECT_EQ(e.u.constant.level, 0);
  ASSERT_EQ(calls[before + 1].op, Op::kWrite);
  const input_event stop = event_of(calls[before + 1]);
  EXPECT_EQ(stop.type, EV_FF);
  EXPECT_EQ(stop.code, 5);
  EXPECT_EQ(stop.value, 0);
  EXPECT_FALSE(d->playing());

  // Force again: the update, then play.
  ASSERT_EQ(d->write({-2.0f, 0.0f, 0.0f}), ForceIo::kOk);
  const auto after = rig.effect_calls();
  ASSERT_EQ(after.size(), before + 4);
  EXPECT_EQ(after[before + 2].op, Op::kUpload);
  EXPECT_EQ(event_of(after[before + 3]).value, 1);
  EXPECT_TRUE(d->playing());
}

TEST(EvdevForceDevice, TheDestructorRemovesTheEffectAndClosesTheNode) {
  Rig rig;
  auto d = rig.opened();
  ASSERT_TRUE(d);
  d.reset();
  const auto removes = rig.sys.calls_of(Op::kRemove);
  ASSERT_EQ(removes.size(), 1u);
  EXPECT_EQ(removes[0].request, static_cast<unsigned long>(EVIOCRMFF));
  int id = -1;
  std::memcpy(&id, removes[0].bytes.data(), sizeof id);
  EXPECT_EQ(id, 5);
  EXPECT_EQ(rig.sys.calls.back().op, Op::kClose);
  EXPECT_TRUE(rig.sys.effects.empty());
}

TEST(EvdevForceDevice, AFiniteEffectIsRestartedAtEveryUpdate) {
  Rig rig;
  EvdevForceOptions o;
  o.effect_length_ms = 0x7fff;
  auto d = rig.opened(o);
  ASSERT_TRUE(d);
  EXPECT_EQ(rig.sys.uploads()[0].replay.length, 0x7fff);
  ASSERT_EQ(d->write({1.0f, 0.0f, 0.0f}), ForceIo::kOk);
  const auto calls = rig.effect_calls();
  ASSERT_EQ(calls.back().op, Op::kWrite);
  EXPECT_EQ(event_of(calls.back()).value, 1);
}

TEST(EvdevForceDevice, ANodeThisUserMayNotOpenSaysHowToGetAccess) {
  Rig rig;
  rig.sys.node(kNode).open_error = -EACCES;
  auto d = rig.open();
  ASSERT_FALSE(d.ok());
  const std::string& m = d.error().message();
  EXPECT_NE(m.find(kNode), std::string::npos) << m;
  EXPECT_NE(m.find("input group"), std::string::npos) << m;
  EXPECT_NE(m.find("uaccess"), std::string::npos) << m;
}

TEST(EvdevForceDevice, ReadWaitsOnlyWhenAskedTo) {
  Rig rig;
  EvdevForceOptions o;
  o.read_wait_ms = 1;
  auto d = rig.opened(o);
  ASSERT_TRUE(d);
  rig.read(*d);
  EXPECT_EQ(rig.sys.calls_of(Op::kPoll).size(), 1u);
  Rig plain;
  auto p = plain.opened();
  ASSERT_TRUE(p);
  plain.read(*p);
  EXPECT_TRUE(plain.sys.calls_of(Op::kPoll).empty());
}

}  // namespace
}  // namespace sculpt::hal::evdev_ff
