// An evdev 6-axis device over a byte-level fake of the kernel's event
// stream (the evdev_ff tests' FakeEvdevIo): what it records for axes,
// buttons, an overrun and an unplug, and which nodes it refuses.

#include "backends/evdev_input/evdev_input_device.h"

#include <gtest/gtest.h>

#include "../evdev_ff/fake_evdev_io.h"
#include "sculpt/hal/parsers/make_parser.h"

namespace sculpt::hal::evdev_input {
namespace {

using evdev_ff::testing::FakeEvdevIo;
using evdev_ff::testing::FakeEvdevNode;
using evdev_ff::testing::FakeEvdevSystem;
using evdev_ff::testing::make_event;
using evdev_ff::testing::Op;

constexpr const char* kNode = "/dev/input/event4";

// A SpaceMouse as hid-generic presents it: six absolute axes of +-350 and
// buttons from BTN_0.
FakeEvdevNode space_mouse() {
  FakeEvdevNode n;
  n.ev_types = {EV_SYN, EV_KEY, EV_ABS, EV_MSC};
  n.abs = {ABS_X, ABS_Y, ABS_Z, ABS_RX, ABS_RY, ABS_RZ};
  for (uint16_t c : n.abs) {
    input_absinfo a{};
    a.minimum = -350;
    a.maximum = 350;
    n.absinfo[c] = a;
  }
  n.keys = {BTN_0, BTN_1, KEY_ESC};
  n.id = {BUS_USB, 0x256f, 0xc635, 1};
  n.name = "3Dconnexion SpaceMouse Compact";
  return n;
}

struct Rig {
  FakeEvdevSystem sys;
  std::vector<std::string> logged;
  std::unique_ptr<EvdevInputDevice> device;
  std::unique_ptr<ReportParser> parser;

  explicit Rig(FakeEvdevNode node, EvdevInputOptions options = {}) {
    sys.nodes[kNode] = std::move(node);
    options.log = [this](std::string_view line) { logged.emplace_back(line); };
    auto d = EvdevInputDevice::open(std::make_unique<FakeEvdevIo>(sys), kNode, options);
    if (!d) {
      ADD_FAILURE() << d.error().message();
      return;
    }
    device = std::move(d).value();
    parser = make_parser(device->info()).value();
  }

  // Reads until a timeout or the removal (bounded), parsing as a replay would.
  std::vector<InputEvent> drain(std::vector<RawEvent>* raws = nullptr, bool* removed = nullptr) {
    std::vector<InputEvent> out;
    for (int i = 0; i < 1000; ++i) {
      RawEvent e;
      const ReadResult r = device->read(e, 0);
      if (r == ReadResult::kTimeout) break;
      if (raws) raws->push_back(e);
      if (r == ReadResult::kRemoved) {
        if (removed) *removed = true;
        break;
      }
      parser->parse(e, out);
    }
    return out;
  }
};

TEST(EvdevInputDevice, OpensWithItsLayoutAndStartsFromItsState) {
  FakeEvdevNode node = space_mouse();
  node.absinfo[ABS_X].value = 175;
  node.held = {BTN_1};
  Rig rig(node);
  ASSERT_TRUE(rig.device);
  const DeviceInfo& info = rig.device->info();
  EXPECT_EQ(info.id(), "evdev:/dev/input/event4");
  EXPECT_EQ(info.vendor_product(), "256f:c635");
  EXPECT_EQ(info.name, "3Dconnexion SpaceMouse Compact");
  EXPECT_EQ(rig.device->layout().button_codes, (std::vector<uint16_t>{BTN_0, BTN_1}))
      << "KEY_ESC is a keyboard's, not a button";
  EvdevLayout recorded;
  ASSERT_EQ(decode_evdev_layout(info.report_descriptor, recorded), EvdevLayoutError::kNone);
  EXPECT_EQ(recorded.axes[0].maximum, 350);

  const auto out = rig.drain();
  ASSERT_EQ(out.size(), 2u) << "the state frame: the cap already pushed, a button held";
  EXPECT_FLOAT_EQ(out[0].axes[kTx], 0.5f);
  EXPECT_EQ(out[1].kind, InputKind::kButton);
  EXPECT_EQ(out[1].button, 1);
  EXPECT_TRUE(out[1].pressed);
}

TEST(EvdevInputDevice, AxesAndButtonsArriveAsFramesAndScanCodesAreNotRecorded) {
  Rig rig(space_mouse());
  ASSERT_TRUE(rig.device);
  rig.drain();
  rig.sys.queue(kNode, {make_event(EV_ABS, ABS_X, -350), make_event(EV_ABS, ABS_Y, 350),
                        make_event(EV_ABS, ABS_RZ, 70), make_event(EV_SYN, SYN_REPORT, 0),
                        make_event(EV_MSC, MSC_SCAN, 0x90001), make_event(EV_KEY, BTN_0, 1),
                        make_event(EV_SYN, SYN_REPORT, 0), make_event(EV_ABS, ABS_Z, 35)});
  std::vector<RawEvent> raws;
  auto out = rig.drain(&raws);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_FLOAT_EQ(out[0].axes[kTx], -1.0f);
  EXPECT_FLOAT_EQ(out[0].axes[kTz], 1.0f);
  EXPECT_FLOAT_EQ(out[0].axes[kRy], -0.2f);
  EXPECT_EQ(out[1].kind, InputKind::kButton);
  EXPECT_EQ(out[1].button, 0);
  size_t recorded = 0;
  for (const RawEvent& e : raws)
    recorded += e.size / kEvdevRecordBytes;
  EXPECT_EQ(recorded, 6u) << "two frames without MSC_SCAN; ABS_Z waits for its SYN_REPORT";
  EXPECT_EQ(rig.device->counters().events, 8);
  EXPECT_EQ(rig.device->counters().frames, 2);

  rig.sys.queue(kNode, {make_event(EV_SYN, SYN_REPORT, 0)});
  out = rig.drain();
  ASSERT_EQ(out.size(), 1u) << "the held-back ABS_Z completes with its frame";
  EXPECT_FLOAT_EQ(out[0].axes[kTy], -0.1f);
}

TEST(EvdevInputDevice, LongFramesSpanSeveralReports) {
  FakeEvdevNode node = space_mouse();
  for (uint16_t b = BTN_2; b <= BTN_9; ++b)
    node.keys.insert(b);
  Rig rig(node);
  ASSERT_TRUE(rig.device);
  std::vector<RawEvent> raws;
  rig.drain(&raws);
  // 6 axes + 10 buttons + SYN_REPORT = 17 records: 3 reports of <= 8.
  ASSERT_EQ(raws.size(), 3u);
  for (const RawEvent& e : raws)
    EXPECT_LE(e.size, RawEvent::kMaxReportBytes);
}

TEST(EvdevInputDevice, AnOverrunIsFollowedByTheStateReadAgain) {
  Rig rig(space_mouse());
  ASSERT_TRUE(rig.device);
  rig.drain();
  // The kernel's queue overran: the frame it cut is lost, and what the
  // device holds now (EVIOCGABS / EVIOCGKEY) is recorded as a frame.
  rig.sys.node(kNode).absinfo[ABS_RX].value = -175;
  rig.sys.node(kNode).held = {BTN_0};
  rig.sys.queue(kNode, {make_event(EV_ABS, ABS_X, 300), make_event(EV_SYN, SYN_DROPPED, 0),
                        make_event(EV_ABS, ABS_Y, 200), make_event(EV_SYN, SYN_REPORT, 0)});
  const size_t abs_reads = rig.sys.calls_of(Op::kGetAbs).size();
  const auto out = rig.drain();
  EXPECT_EQ(rig.device->counters().overruns, 1);
  EXPECT_EQ(rig.sys.calls_of(Op::kGetAbs).size(), abs_reads + 6);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_FLOAT_EQ(out[0].axes[kTx], 0.0f) << "ABS_X 300 came before the overrun: not applied";
  EXPECT_FLOAT_EQ(out[0].axes[kRx], -0.5f);
  EXPECT_EQ(out[1].kind, InputKind::kButton);
  EXPECT_TRUE(out[1].pressed);
}

TEST(EvdevInputDevice, UnplugDeliversWhatWasReadThenRemovedForGood) {
  Rig rig(space_mouse());
  ASSERT_TRUE(rig.device);
  rig.drain();
  rig.sys.queue(kNode, {make_event(EV_ABS, ABS_X, 35), make_event(EV_SYN, SYN_REPORT, 0)});
  RawEvent e;
  // Read the frame, then unplug before the next read.
  ASSERT_EQ(rig.device->read(e, 0), ReadResult::kEvent);
  rig.sys.gone = true;
  bool removed = false;
  rig.drain(nullptr, &removed);
  EXPECT_TRUE(removed);
  EXPECT_EQ(rig.device->read(e, 0), ReadResult::kRemoved);
  EXPECT_EQ(e.kind, RawEventKind::kRemoved);
  ASSERT_EQ(rig.logged.size(), 1u);
  EXPECT_NE(rig.logged[0].find("unplugged"), std::string::npos) << rig.logged[0];
}

TEST(EvdevInputDevice, StrayBytesAreCountedAndLoggedOnce) {
  Rig rig(space_mouse());
  ASSERT_TRUE(rig.device);
  rig.drain();
  for (int i = 0; i < 3; ++i)
    rig.sys.node(kNode).reads.push_back(std::vector<uint8_t>(5, 0xab));
  rig.sys.queue(kNode, {make_event(EV_ABS, ABS_X, 350), make_event(EV_SYN, SYN_REPORT, 0)});
  std::vector<InputEvent> out;
  for (int i = 0; i < 8; ++i) {
    auto more = rig.drain();
    out.insert(out.end(), more.begin(), more.end());
  }
  EXPECT_EQ(rig.device->counters().stray_bytes, 15);
  EXPECT_EQ(rig.logged.size(), 1u);
  ASSERT_EQ(out.size(), 1u) << "the good frame after the garbage still arrives";
  EXPECT_FLOAT_EQ(out[0].axes[kTx], 1.0f);
}

TEST(EvdevInputDevice, ARelativeDeviceIsReleasedWhenItFallsSilent) {
  FakeEvdevNode node = space_mouse();
  node.ev_types = {EV_SYN, EV_KEY, EV_REL};
  node.abs.clear();
  node.rel = {REL_X, REL_Y, REL_Z, REL_RX, REL_RY, REL_RZ};
  EvdevInputOptions options;
  options.rel_release_ms = 0;  // released at the first read that finds nothing
  Rig rig(node, options);
  ASSERT_TRUE(rig.device);
  EXPECT_EQ(rig.device->layout().axes[0].kind, EvdevAxisKind::kRelative);
  rig.drain();
  rig.sys.queue(kNode, {make_event(EV_REL, REL_X, 350), make_event(EV_SYN, SYN_REPORT, 0)});
  const auto out = rig.drain();
  ASSERT_EQ(out.size(), 2u) << "the frame, then the release frame at the next silence";
  EXPECT_FLOAT_EQ(out[0].axes[kTx], 1.0f);
  EXPECT_FLOAT_EQ(out[1].axes[kTx], 0.0f);
  EXPECT_EQ(rig.device->counters().releases, 1);
  EXPECT_TRUE(rig.drain().empty()) << "released once, not at every silence";
}

TEST(EvdevInputDevice, RefusesWhatIsNotASixAxisController) {
  FakeEvdevSystem sys;
  FakeEvdevNode pad = space_mouse();
  pad.keys = {BTN_SOUTH, BTN_EAST};
  sys.nodes["/dev/input/event1"] = pad;
  FakeEvdevNode five = space_mouse();
  five.abs.erase(ABS_RY);
  sys.nodes["/dev/input/event2"] = five;
  FakeEvdevNode flat = space_mouse();
  flat.absinfo[ABS_Z].maximum = -350;
  sys.nodes["/dev/input/event3"] = flat;
  sys.nodes["/dev/input/event5"] = space_mouse();
  sys.nodes["/dev/input/event5"].open_error = -EACCES;

  auto open = [&](const char* node) {
    auto d = EvdevInputDevice::open(std::make_unique<FakeEvdevIo>(sys), node);
    EXPECT_FALSE(d.ok()) << node;
    return d.ok() ? std::string() : d.error().message();
  };
  EXPECT_NE(open("/dev/input/event1").find("gamepad"), std::string::npos);
  EXPECT_NE(open("/dev/input/event2").find("no axis RY"), std::string::npos);
  EXPECT_NE(open("/dev/input/event3").find("axis Z has an empty range"), std::string::npos);
  EXPECT_NE(open("/dev/input/event5").find("input group"), std::string::npos);
  EXPECT_NE(open("/dev/input/event9").find("/dev/input/event9"), std::string::npos);
}

}  // namespace
}  // namespace sculpt::hal::evdev_input
