#include "sculpt/sim/synth/session_script.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sculpt/hal/parsers/make_parser.h"

namespace sculpt::sim {
namespace {

constexpr float kPi = 3.14159265f;

// The script steers through the real pipeline: the pose it reaches must be on
// the path it was asked to follow, for both report layouts.
TEST(SessionScript, FollowsPathsThroughTheRealPipeline) {
  for (uint16_t product : {uint16_t{0xc626}, uint16_t{0xc635}}) {
    const uint16_t vendor = product == 0xc626 ? 0x046d : 0x256f;
    SessionScript s(scripted_device(vendor, product), scripted_normalizer(), 250);
    const Path helix = helix_path(glm::vec3(10, 20, 30), glm::vec3(0, 1, 0), 8, 1.5f, 20);
    EXPECT_NEAR(glm::length(helix(0) - glm::vec3(10, 20, 30)), 8.0f, 1e-4f);  // on the circle
    s.place(helix(0));
    float worst = 0;
    const int samples = 40;
    for (int k = 1; k <= samples; ++k) {
      const float a = static_cast<float>(k - 1) / samples, b = static_cast<float>(k) / samples;
      s.follow([&](float t) { return helix(a + (b - a) * t); }, 0.05f);
      worst = std::max(worst, glm::length(s.pose().position - helix(b)));
    }
    EXPECT_LT(worst, 1.0f) << std::hex << product;  // within a voxel all along
    const glm::quat target = glm::angleAxis(kPi / 3, glm::vec3(0, 0, 1));
    s.follow(line_path(s.pose().position, s.pose().position), 0.5f,
             [&](float t) { return glm::slerp(glm::quat(1, 0, 0, 0), target, t); });
    EXPECT_GT(std::abs(glm::dot(s.pose().orientation, target)), 0.999f);
  }
}

TEST(SessionScript, EmitsOnlyReportsTheParserUnderstands) {
  SessionScript s(scripted_device(0x256f, 0xc633), scripted_normalizer(),
                  500);  // Enterprise: numbered buttons
  s.place(glm::vec3(0));
  s.press();
  s.follow(zigzag_path(glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), 20, 4, 2), 0.3f);
  s.release();
  const Session session = s.finish();
  auto parser = hal::make_parser(session.header.device);
  ASSERT_TRUE(parser.ok());
  std::vector<hal::InputEvent> out;
  int presses = 0, releases = 0;
  for (const SessionRecord& r : session.records) {
    if (r.kind != SessionRecord::Kind::kEvent) continue;
    out.clear();
    (*parser)->parse(r.event, out);
    for (const hal::InputEvent& e : out) {
      if (e.kind == hal::InputKind::kButton) (e.pressed ? presses : releases)++;
    }
  }
  EXPECT_EQ((*parser)->counters().unknown_reports, 0);
  EXPECT_EQ((*parser)->counters().short_reports, 0);
  EXPECT_EQ(presses, 1);
  EXPECT_EQ(releases, 1);
}

TEST(SessionScript, PathsStartAndEndWhereTheySay) {
  const glm::vec3 o(1, 2, 3), x(1, 0, 0), y(0, 1, 0);
  EXPECT_EQ(line_path(o, o + x)(1.0f), o + x);
  EXPECT_LT(glm::length(arc_path(o, x, y, 5, 0, kPi)(1.0f) - (o - 5.0f * x)), 1e-5f);
  EXPECT_LT(glm::length(spiral_path(o, x, y, 1, 4, 1)(1.0f) - (o + 4.0f * x)), 1e-4f);
  EXPECT_EQ(zigzag_path(o, x, y, 10, 2, 3)(0.0f), o);
  EXPECT_LT(
      glm::length(zigzag_path(o, x, y, 10, 2, 3)(1.0f / 6) - (o + glm::vec3(10.0f / 6, 2, 0))),
      1e-4f);
}

}  // namespace
}  // namespace sculpt::sim
