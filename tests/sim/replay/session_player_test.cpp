#include "sculpt/sim/replay/session_player.h"

#include <gtest/gtest.h>

namespace sculpt::sim {
namespace {

// A clock that only moves when the player sleeps: pacing becomes exact.
struct FakeClock {
  int64_t now = 5'000;
  std::vector<int64_t> sleeps;
  PlayerClock clock() {
    return {[this] { return now; },
            [this](int64_t t) {
              sleeps.push_back(t);
              now = std::max(now, t);
            }};
  }
};

Session timed_session(std::initializer_list<int64_t> times) {
  Session s;
  for (int64_t t : times)
    s.records.push_back(SessionRecord::of(hal::RawEvent::sync(t)));
  return s;
}

TEST(SessionPlayer, PacesRecordsAtTheirRecordedSpacingTimesTheSpeed) {
  const Session s = timed_session({1000, 1000, 3000, 7000});
  FakeClock c;
  SessionPlayer p(s, 2.0, false, c.clock());
  std::vector<int64_t> played_at;
  while (const SessionRecord* r = p.next())
    played_at.push_back(c.now), (void)r;
  EXPECT_EQ(played_at, (std::vector<int64_t>{5000, 5000, 6000, 8000}));
  EXPECT_TRUE(p.at_end());
  EXPECT_EQ(p.progress(), 1.0);
}

TEST(SessionPlayer, APauseOfADayInTheRecordingPlaysAsTwoSeconds) {
  const int64_t day = int64_t{86'400} * 1'000'000'000;
  const Session s = timed_session({1000, 2000, 2000 + day, 3000 + day});
  FakeClock c;
  SessionPlayer p(s, 1.0, false, c.clock());
  std::vector<int64_t> played_at;
  while (p.next() != nullptr)
    played_at.push_back(c.now);
  const int64_t cap = SessionPlayer::kMaxPacedGapNs;
  EXPECT_EQ(played_at, (std::vector<int64_t>{5000, 6000, 6000 + cap, 7000 + cap}));
}

TEST(SessionPlayer, FastNeverWaits) {
  const Session s = timed_session({0, 1'000'000'000, 2'000'000'000});
  FakeClock c;
  SessionPlayer p(s, 1.0, true, c.clock());
  int n = 0;
  while (p.next())
    ++n;
  EXPECT_EQ(n, 3);
  EXPECT_TRUE(c.sleeps.empty());
}

TEST(SessionPlayer, PauseStepAndResume) {
  const Session s = timed_session({0, 100, 200, 300});
  FakeClock c;
  SessionPlayer p(s, 1.0, false, c.clock());
  ASSERT_NE(p.next(), nullptr);
  p.pause();
  EXPECT_EQ(p.next(), nullptr);
  const int64_t before = c.now;
  ASSERT_NE(p.step(), nullptr);  // one record, no waiting
  EXPECT_EQ(c.now, before);
  EXPECT_EQ(p.position(), 2u);
  c.now += 1'000'000;  // a long pause
  p.resume();
  const int64_t resumed = c.now;
  ASSERT_NE(p.next(), nullptr);
  EXPECT_EQ(c.now, resumed);  // due at once after a resume, not in the past
  ASSERT_NE(p.next(), nullptr);
  EXPECT_EQ(c.now, resumed + 100);
}

TEST(SessionPlayer, SeekForwardCatchesUpWithoutWaitingAndBackwardRestarts) {
  const Session s = timed_session({0, 100, 200, 300, 400});
  FakeClock c;
  SessionPlayer p(s, 1.0, false, c.clock());
  EXPECT_FALSE(p.seek(300));
  while (p.position() < 3)
    ASSERT_NE(p.next(), nullptr);
  EXPECT_TRUE(c.sleeps.empty());  // records before the target are delivered at once
  ASSERT_NE(p.next(), nullptr);   // t = 300: pacing restarts here
  ASSERT_NE(p.next(), nullptr);   // t = 400: 100 later
  EXPECT_EQ(c.sleeps.back(), c.now);
  EXPECT_TRUE(p.seek(100));  // backwards: the consumer must start over
  EXPECT_EQ(p.position(), 0u);
}

}  // namespace
}  // namespace sculpt::sim
