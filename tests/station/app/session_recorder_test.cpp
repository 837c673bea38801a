#include "sculpt/station/app/session_recorder.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

#include "scratch_dir.h"
#include "sculpt/sim/session/session_file.h"

namespace sculpt::station {
namespace {

hal::RawEvent report(int64_t t) {
  return hal::RawEvent::sync(t);
}

// The times of the reports in a session file.
std::vector<int64_t> report_times(const std::filesystem::path& path) {
  auto session = sim::read_session_file(path);
  EXPECT_TRUE(session.ok()) << session.error().message();
  std::vector<int64_t> times;
  for (const sim::SessionRecord& r : session->records) {
    if (r.kind == sim::SessionRecord::Kind::kEvent) times.push_back(r.event.t_ns);
  }
  return times;
}

// A file holds the reports the station applied while it recorded: those
// tapped but not yet applied when it starts are in it, those applied before
// are not (the opening has them), nor those still in flight when it stops,
// which go into the next recording instead.
TEST(SessionRecorder, HoldsTheReportsAppliedWhileItRecorded) {
  test::ScratchDir dir;
  SessionRecorder r;
  for (int t = 1; t <= 5; ++t)
    r.raw(report(t));
  r.release_until(3);  // applied before the recording: let go
  const sim::Command undo{sim::CommandKind::kUndo, 0, {}};
  ASSERT_TRUE(r.start(dir.path() / "a.scs", {}, {undo}, 3).ok());
  r.raw(report(20));
  r.raw(report(30));
  r.release_until(20);  // 30 is still in flight when the recording stops
  auto n = r.stop();
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(*n, 4);  // the opening command and three reports
  EXPECT_EQ(report_times(dir.path() / "a.scs"), (std::vector<int64_t>{4, 5, 20}));

  r.raw(report(40));
  EXPECT_EQ(r.raw_kept(), 2u);
  r.release_until(35);  // 30 applied while nothing records: let go
  EXPECT_EQ(r.raw_kept(), 1u);
  ASSERT_TRUE(r.start(dir.path() / "b.scs", {}, {}, 35).ok());
  r.release_until(40);
  ASSERT_TRUE(r.stop().ok());
  EXPECT_EQ(report_times(dir.path() / "b.scs"), (std::vector<int64_t>{40}));
}

// Until the station says what it applied, every report counts as applied
// (a recorder fed by hand writes what it is given).
TEST(SessionRecorder, WritesEveryReportWhenNothingIsReleased) {
  test::ScratchDir dir;
  SessionRecorder r;
  ASSERT_TRUE(r.start(dir.path() / "a.scs", {}, {}, 0).ok());
  r.raw(report(10));
  r.raw(report(20));
  ASSERT_TRUE(r.stop().ok());
  EXPECT_EQ(report_times(dir.path() / "a.scs"), (std::vector<int64_t>{10, 20}));
}

}  // namespace
}  // namespace sculpt::station
