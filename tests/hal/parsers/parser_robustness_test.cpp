// Devices send garbage sometimes (a flaky cable, a firmware we never saw):
// random bytes must never crash a parser or produce an axis outside [-1, 1].
// Deterministic (fixed seed); run under -DSCULPT_SANITIZE=address,undefined in
// CI to catch out-of-bounds reads the assertions cannot see.

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "multi_axis_descriptor.h"
#include "sculpt/hal/parsers/hid_descriptor.h"
#include "sculpt/hal/parsers/make_parser.h"
#include "sculpt/hal/parsers/spacemouse_parser.h"
#include "sculpt/hal/types/quirks.h"

namespace sculpt::hal {
namespace {

struct Lcg {
  uint32_t s;
  uint32_t next() {
    s = s * 1664525u + 1013904223u;
    return s >> 8;
  }
};

// Reports with a plausible id (so the decoding paths run) and any length 0..80.
std::vector<uint8_t> random_report(Lcg& r) {
  static constexpr uint8_t kIds[] = {1, 2, 3, 0x17, 0x1c, 4, 0xff};
  std::vector<uint8_t> b(r.next() % 81);
  for (uint8_t& x : b)
    x = static_cast<uint8_t>(r.next());
  if (!b.empty()) b[0] = kIds[r.next() % 7];
  return b;
}

void expect_sane(const std::vector<InputEvent>& out) {
  for (const InputEvent& e : out) {
    for (float a : e.axes) {
      ASSERT_TRUE(a >= -1.0f && a <= 1.0f) << a;
    }
    if (e.kind == InputKind::kButton) {
      ASSERT_TRUE(e.button >= 0 && e.button < 128) << e.button;
    }
    if (e.kind == InputKind::kBattery) {
      ASSERT_TRUE(e.battery_percent >= 0 && e.battery_percent <= 100);
    }
  }
}

TEST(ParserRobustness, RandomReportsIntoEveryKnownDevice) {
  Lcg r{12345};
  for (const DeviceQuirks& q : all_quirks()) {
    if (q.kind != QuirkKind::kSpaceMouse) continue;
    SpaceMouseParser p(q);
    std::vector<InputEvent> out;
    for (int i = 0; i < 5000; ++i) {
      out.clear();
      p.parse(RawEvent::report(i, random_report(r)), out);
      expect_sane(out);
    }
    EXPECT_EQ(p.counters().reports, 5000) << q.name;
  }
}

TEST(ParserRobustness, RandomReportsIntoTheDescriptorParser) {
  DeviceInfo info;
  info.backend = "sim";
  info.path = "pad";
  info.report_descriptor = test::multi_axis_descriptor(false);
  auto parser = make_parser(info);
  ASSERT_TRUE(parser.ok());
  Lcg r{777};
  std::vector<InputEvent> out;
  for (int i = 0; i < 20000; ++i) {
    out.clear();
    (*parser)->parse(RawEvent::report(i, random_report(r)), out);
    expect_sane(out);
  }
}

TEST(ParserRobustness, MutatedDescriptorsParseOrFailCleanly) {
  const std::vector<uint8_t> base = test::multi_axis_descriptor(true);
  Lcg r{4242};
  int ok = 0, failed = 0;
  for (int i = 0; i < 20000; ++i) {
    std::vector<uint8_t> d = base;
    const int edits = 1 + static_cast<int>(r.next() % 4);
    for (int k = 0; k < edits; ++k)
      d[r.next() % d.size()] = static_cast<uint8_t>(r.next());
    if (r.next() % 4 == 0) d.resize(r.next() % d.size());
    const auto layout = parse_hid_descriptor(d);
    if (!layout) {
      ++failed;
      EXPECT_EQ(layout.error().message().rfind("report descriptor: ", 0), 0u)
          << layout.error().message();
      continue;
    }
    ++ok;
    for (const auto& a : layout->axes) {
      if (a) {
        ASSERT_LE(a->bit_size, 32u);
      }
    }
  }
  // Both outcomes occur: the mutations reach the error paths and the success path.
  EXPECT_GT(ok, 100);
  EXPECT_GT(failed, 100);
}

}  // namespace
}  // namespace sculpt::hal
