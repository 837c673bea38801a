// libFuzzer target: what an evdev force-feedback device (or something behind
// its node pretending to be one) hands the read path: the axis ranges of
// EVIOCGABS and the bytes of read(), fed as input_event records through
// EvdevForceDevice over the tests' fake evdev edge (CI has no FF device and
// no /dev/uinput). Each read is followed by a write of a force from the
// position, as the haptic loop does.
//
// Input: byte 0 = device flags (bit 0 ABS_Z present, bit 1 gamepad buttons
// instead of joystick ones, bit 2 FF_AUTOCENTER); then up to 24 bytes of
// minimum/maximum int32 pairs for ABS_X, ABS_Y, ABS_Z (little-endian);
// then chunks, each a length byte and that many bytes as one read()'s
// answer; length 0xff instead makes the next read fail with EIO, 0xfe with
// ENODEV. Checks: no crash; positions finite and within the workspace;
// only declared buttons; the effect never above full level; once removed,
// removed for good. Seeds: corpus/evdev_ff.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>

#include "backends/evdev_ff/evdev_force_device.h"
#include "hal/backends/evdev_ff/fake_evdev_io.h"

namespace {

using namespace sculpt::hal;
using namespace sculpt::hal::evdev_ff;

constexpr const char* kNode = "/dev/input/event0";

int32_t int32_at(const uint8_t* p) {
  uint32_t v = 0;
  for (int i = 3; i >= 0; --i)
    v = (v << 8) | p[i];
  return static_cast<int32_t>(v);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const uint8_t flags = data[0];
  size_t at = 1;

  testing::FakeEvdevSystem sys;
  testing::FakeEvdevNode& node = sys.nodes[kNode];
  node.ev_types = {EV_SYN, EV_KEY, EV_ABS, EV_FF};
  node.ff = {FF_CONSTANT, FF_GAIN};
  if (flags & 4) node.ff.insert(FF_AUTOCENTER);
  node.abs = {ABS_X, ABS_Y};
  if (flags & 1) node.abs.insert(ABS_Z);
  const uint16_t axes[3] = {ABS_X, ABS_Y, ABS_Z};
  for (uint16_t axis : axes) {
    input_absinfo a{};
    a.minimum = 0;
    a.maximum = 1023;
    if (at + 8 <= size) {
      a.minimum = int32_at(data + at);
      a.maximum = int32_at(data + at + 4);
      at += 8;
    }
    node.absinfo[axis] = a;
  }
  if (flags & 2) {
    node.keys = {BTN_SOUTH, BTN_EAST, BTN_NORTH, BTN_WEST};
  } else {
    node.keys = {BTN_TRIGGER, BTN_THUMB, BTN_THUMB2, BTN_TOP, BTN_TRIGGER_HAPPY1};
  }
  const uint32_t declared = (1u << node.keys.size()) - 1u;
  node.id = {BUS_USB, 0x1234, 0x5678, 1};
  node.name = "fuzz";

  EvdevForceOptions options;
  auto opened = EvdevForceDevice::open(std::make_unique<testing::FakeEvdevIo>(sys), kNode, options);
  if (!opened.ok()) return 0;
  std::unique_ptr<EvdevForceDevice> device = std::move(opened).value();
  const float half = options.workspace_half_range_mm;

  bool removed = false;
  while (at < size) {
    const uint8_t length = data[at++];
    if (length == 0xff) {
      sys.failures[testing::Op::kRead].push_back(-EIO);
    } else if (length == 0xfe) {
      sys.failures[testing::Op::kRead].push_back(-ENODEV);
    } else {
      const size_t n = std::min<size_t>(length, size - at);
      node.reads.emplace_back(data + at, data + at + n);
      at += n;
    }
    ForceDeviceState s;
    const ForceIo r = device->read(s);
    if (removed && r != ForceIo::kRemoved) __builtin_trap();
    if (r == ForceIo::kRemoved) {
      removed = true;
      continue;
    }
    for (int i = 0; i < 3; ++i) {
      if (!std::isfinite(s.position_mm[i]) || std::fabs(s.position_mm[i]) > half) __builtin_trap();
    }
    if ((s.buttons & ~declared) != 0) __builtin_trap();
    // A spring toward the centre, as a law would ask for.
    const ForceIo w = device->write(-0.1f * s.position_mm);
    if (w == ForceIo::kRemoved) removed = true;
    if (device->effect().level < 0 || device->effect().level > kMaxConstantLevel) __builtin_trap();
  }
  device->zero();
  return 0;
}
