#include "sculpt/station/app/input_statistics.h"

#include <gtest/gtest.h>

namespace sculpt::station {
namespace {

constexpr int64_t kMs = 1'000'000;

TEST(InputStatistics, ADabCountsFromItsReportToTheMeshOfItsChange) {
  InputStatistics s;
  s.note_dabs(2, 10 * kMs);  // two dabs of one report
  EXPECT_TRUE(s.dabs_waiting());
  s.submitted(1, 10 * kMs);
  EXPECT_FALSE(s.dabs_waiting());
  s.note_dabs(1, 12 * kMs);
  s.submitted(2, 12 * kMs);
  s.ready(1, 1, 14 * kMs);  // change 1 meshed: its dabs took 4 ms, change 2's waits
  EXPECT_EQ(s.session_latency().count, 2);
  EXPECT_EQ(s.recent_latency().max_us, 4000.0);
  s.ready(2, 2, 20 * kMs);  // 8 ms
  EXPECT_EQ(s.session_latency().count, 3);
  EXPECT_EQ(s.recent_latency().max_us, 8000.0);
  EXPECT_EQ(s.session_latency().max_us, 8000.0);
  s.ready(2, 2, 30 * kMs);  // nothing left to count
  EXPECT_EQ(s.session_latency().count, 3);
}

TEST(InputStatistics, TheSlowestDabsAreKeptSlowestFirstWithWhereTheirTimeWent) {
  InputStatistics s;
  // Twelve dabs, one change each: dab i reported at 100 i ms, handed over
  // i ms later and meshed (7 i mod 12) ms after that, so the slowest are
  // not the latest.
  for (int64_t i = 1; i <= 12; ++i) {
    const int64_t report = 100 * i * kMs;
    const int64_t handed = report + i * kMs;
    s.note_dabs(1, report);
    s.submitted(static_cast<uint64_t>(i), handed);
    s.ready(static_cast<uint64_t>(i), static_cast<uint64_t>(i), handed + (7 * i % 12) * kMs);
  }
  const auto slow = s.slowest();
  ASSERT_EQ(slow.size(), InputStatistics::kSlowestKept);
  for (size_t k = 1; k < slow.size(); ++k)
    EXPECT_GE(slow[k - 1].first_mesh_us, slow[k].first_mesh_us);
  // The slowest is i = 10 (10 + 10 ms); three dabs took 16 ms, four 12 ms.
  EXPECT_EQ(slow[0].change, 10u);
  EXPECT_EQ(slow[0].first_mesh_us, 20000.0);
  EXPECT_EQ(slow[0].handed_over_us, 10000.0);
  EXPECT_EQ(slow[1].first_mesh_us, 16000.0);
  // The four 8 ms and 4 ms dabs are the ones left out.
  EXPECT_EQ(slow.back().first_mesh_us, 12000.0);
}

TEST(InputStatistics, FullDetailCanComeLaterThanTheFirstMesh) {
  InputStatistics s;
  s.note_dabs(1, 10 * kMs);
  s.submitted(1, 10 * kMs);
  s.ready(1, 0, 13 * kMs);  // shown coarse after 3 ms
  EXPECT_EQ(s.session_latency().max_us, 3000.0);
  EXPECT_EQ(s.full_detail_latency().count, 0);
  s.ready(1, 1, 40 * kMs);  // full detail after 30 ms
  EXPECT_EQ(s.session_latency().count, 1);
  EXPECT_EQ(s.full_detail_latency().max_us, 30000.0);
}

TEST(InputStatistics, ADabThatChangedNothingIsShownWhenItIsSubmitted) {
  InputStatistics s;
  s.note_dabs(1, 10 * kMs);
  s.submitted(1, 10 * kMs);
  s.ready(1, 1, 15 * kMs);
  s.note_dabs(1, 20 * kMs);  // a dab in the air: the mesher's change stays 1
  s.submitted(1, 21 * kMs);
  EXPECT_EQ(s.session_latency().count, 2);
  EXPECT_EQ(s.full_detail_latency().count, 2);
  EXPECT_EQ(s.recent_latency().max_us, 5000.0);  // not the 100 ms until the next change
  s.note_dabs(1, 30 * kMs);
  s.submitted(2, 31 * kMs);  // a real change waits for its mesh
  EXPECT_EQ(s.session_latency().count, 2);
  s.ready(2, 1, 34 * kMs);
  EXPECT_EQ(s.session_latency().count, 3);
  EXPECT_EQ(s.full_detail_latency().count, 2);
}

TEST(InputStatistics, ABallBrushDabWaitsForThePreviewThatShowsIt) {
  // A smoothing press: the first dab changes nothing (no preview yet), the
  // second brings a preview of both, the third waits for the press's end.
  InputStatistics s;
  s.note_dabs(1, 10 * kMs, 0, 0, /*unshown=*/1);
  EXPECT_FALSE(s.dabs_waiting());
  s.submitted(1, 10 * kMs);  // nothing changed: no mesh to wait for, yet
  s.ready(1, 1, 11 * kMs);
  EXPECT_EQ(s.session_latency().count, 0);
  s.note_dabs(1, 12 * kMs, 0, 0, /*unshown=*/0);  // the preview
  s.submitted(2, 13 * kMs);
  s.ready(2, 2, 16 * kMs);
  EXPECT_EQ(s.session_latency().count, 2);
  EXPECT_EQ(s.recent_latency().max_us, 6000.0);  // the first dab's: 10 to 16 ms
  EXPECT_EQ(s.first_picture_latency().max_us, 6000.0);
  s.note_dabs(1, 20 * kMs, 0, 0, /*unshown=*/1);
  s.submitted(2, 20 * kMs);
  EXPECT_EQ(s.session_latency().count, 2);
  s.still_unshown(0);  // the press ended: the brush applied for real
  s.submitted(3, 30 * kMs);
  s.ready(3, 3, 32 * kMs);
  EXPECT_EQ(s.session_latency().count, 3);
  EXPECT_EQ(s.session_latency().max_us, 12000.0);
}

TEST(InputStatistics, TheReportRateIsOverAboutASecond) {
  InputStatistics s;
  EXPECT_LT(s.reader_samples(0, 0), 0);            // the start
  EXPECT_LT(s.reader_samples(100, 500 * kMs), 0);  // not a second yet
  EXPECT_DOUBLE_EQ(s.reader_samples(250, 1000 * kMs), 250.0);
  s.restart_report_rate();  // unplugged
  EXPECT_LT(s.reader_samples(260, 1100 * kMs), 0);
  EXPECT_DOUBLE_EQ(s.reader_samples(360, 2100 * kMs), 100.0);
}

}  // namespace
}  // namespace sculpt::station
