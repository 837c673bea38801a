#include "sculpt/station/app/session_recorder.h"

#include <gtest/gtest.h>

#include "scratch_dir.h"
#include "sculpt/sim/session/session_file.h"

namespace sculpt::station {
namespace {

hal::RawEvent report(int64_t t) {
  return hal::RawEvent::sync(t);
}

TEST(SessionRecorder, KeepsReportsOnlyWhileRecordingOrArmed) {
  test::ScratchDir dir;
  SessionRecorder r;
  for (int i = 0; i < 5; ++i)
    r.raw(report(i));  // nothing records: dropped
  const sim::Command undo{sim::CommandKind::kUndo, 0, {}};
  ASSERT_TRUE(r.start(dir.path() / "a.scs", {}, {undo}, 10).ok());
  r.raw(report(20));
  auto n = r.stop();
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(*n, 2);   // the opening command and the one report
  r.raw(report(30));  // stopped: dropped again

  SessionRecorder armed;
  armed.arm();
  armed.raw(report(1));  // before start: kept for it
  ASSERT_TRUE(armed.start(dir.path() / "b.scs", {}, {}, 0).ok());
  auto m = armed.stop();
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(*m, 1);
  auto session = sim::read_session_file(dir.path() / "b.scs");
  ASSERT_TRUE(session.ok()) << session.error().message();
  EXPECT_EQ(session->records.size(), 1u);
}

}  // namespace
}  // namespace sculpt::station
