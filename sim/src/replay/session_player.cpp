#include "sculpt/sim/replay/session_player.h"

#include <algorithm>
#include <chrono>
#include <thread>

namespace sculpt::sim {

PlayerClock PlayerClock::steady() {
  using clock = std::chrono::steady_clock;
  return {
      [] {
        return std::chrono::duration_cast<std::chrono::nanoseconds>(clock::now().time_since_epoch())
            .count();
      },
      [](int64_t t) {
        std::this_thread::sleep_until(clock::time_point(std::chrono::nanoseconds(t)));
      }};
}

SessionPlayer::SessionPlayer(const Session& session, double speed, bool fast, PlayerClock clock)
    : session_(session), speed_(speed > 0 ? speed : 1.0), fast_(fast), clock_(std::move(clock)) {
  restart_pacing();
}

void SessionPlayer::restart_pacing() {
  // The next record is due now; later ones follow at their recorded spacing.
  wall_origin_ns_ = clock_.now_ns();
  session_origin_t_ns_ = at_end() ? 0 : session_.records[next_].t_ns();
}

int64_t SessionPlayer::due_ns() const {
  if (at_end() || fast_) return clock_.now_ns();
  const int64_t t = session_.records[next_].t_ns();
  if (t < catch_up_until_t_ns_) return clock_.now_ns();
  return wall_origin_ns_ +
         static_cast<int64_t>(static_cast<double>(t - session_origin_t_ns_) / speed_);
}

const SessionRecord* SessionPlayer::next() {
  if (paused_ || at_end()) return nullptr;
  const SessionRecord& r = session_.records[next_];
  if (!fast_ && r.t_ns() >= catch_up_until_t_ns_ && catch_up_until_t_ns_ != INT64_MIN) {
    // The seek target is reached: pace from here on.
    catch_up_until_t_ns_ = INT64_MIN;
    restart_pacing();
  }
  if (next_ > 0) {
    // A pause in the recording longer than kMaxPacedGapNs plays as that
    // long: a session resumed the next day must not sleep a day.
    const int64_t gap = r.t_ns() - session_.records[next_ - 1].t_ns();
    if (gap > kMaxPacedGapNs) session_origin_t_ns_ += gap - kMaxPacedGapNs;
  }
  const int64_t due = due_ns();
  if (clock_.now_ns() < due) clock_.sleep_until_ns(due);
  ++next_;
  return &r;
}

const SessionRecord* SessionPlayer::step() {
  if (at_end()) return nullptr;
  return &session_.records[next_++];
}

void SessionPlayer::pause() {
  paused_ = true;
}

void SessionPlayer::resume() {
  if (!paused_) return;
  paused_ = false;
  restart_pacing();
}

void SessionPlayer::set_speed(double speed) {
  if (speed <= 0) return;
  speed_ = speed;
  restart_pacing();
}

bool SessionPlayer::seek(int64_t t_ns) {
  const auto& records = session_.records;
  const size_t target = static_cast<size_t>(
      std::lower_bound(records.begin(), records.end(), t_ns,
                       [](const SessionRecord& r, int64_t t) { return r.t_ns() < t; }) -
      records.begin());
  const bool backwards = target < next_;
  // The consumer's state is the result of every record before the target, so
  // it must see them all: from the start when going back, from here otherwise.
  if (backwards) next_ = 0;
  catch_up_until_t_ns_ = t_ns;
  return backwards;
}

double SessionPlayer::progress() const {
  const int64_t span = session_.end_t_ns() - session_.start_t_ns();
  if (at_end() || span <= 0) return at_end() ? 1.0 : 0.0;
  return static_cast<double>(session_.records[next_].t_ns() - session_.start_t_ns()) /
         static_cast<double>(span);
}

}  // namespace sculpt::sim
