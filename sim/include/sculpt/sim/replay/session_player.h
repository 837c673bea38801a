#pragma once
// Steps through a session's records in order, paced against a clock: real
// time, a speed factor, or as fast as possible; with pause, single step and
// seek. The replay loop consumes the records synchronously, so what it
// computes depends only on the records, never on the pacing: a replay at any
// speed reproduces the same sculpture.

#include <cstdint>
#include <functional>

#include "sculpt/sim/session/session.h"

namespace sculpt::sim {

/// The player's view of time, replaceable in tests.
struct PlayerClock {
  std::function<int64_t()> now_ns;              ///< monotonic ns
  std::function<void(int64_t)> sleep_until_ns;  ///< returns at or after the time
  static PlayerClock steady();
};

class SessionPlayer {
 public:
  /// The longest pause in a recording that pacing reproduces (session
  /// time); a longer one plays as this long.
  static constexpr int64_t kMaxPacedGapNs = 2'000'000'000;

  /// speed: 1 = real time, 2 = twice as fast; fast = no waiting at all.
  SessionPlayer(const Session& session, double speed = 1.0, bool fast = false,
                PlayerClock clock = PlayerClock::steady());

  /// The next record, after waiting until it is due; nullptr at the end, or
  /// while paused (then call step()).
  const SessionRecord* next();
  /// While paused: the next record at once.
  const SessionRecord* step();
  void pause();
  void resume();
  bool paused() const { return paused_; }
  void set_speed(double speed);
  /// Moves to the first record at or after t_ns. Returns true when that is
  /// behind the current position: the consumer must reset its state (a new
  /// volume) before the records are replayed from the start. Records before
  /// t_ns are delivered without waiting.
  bool seek(int64_t t_ns);

  /// Clock time at which the next record is due (now when not pacing).
  int64_t due_ns() const;
  const PlayerClock& clock() const { return clock_; }

  size_t position() const { return next_; }
  bool at_end() const { return next_ >= session_.records.size(); }
  /// Fraction of the session's duration played, 0..1.
  double progress() const;

 private:
  void restart_pacing();

  const Session& session_;
  double speed_;
  bool fast_;
  PlayerClock clock_;
  size_t next_ = 0;
  bool paused_ = false;
  int64_t catch_up_until_t_ns_ = INT64_MIN;  // seek target: no waiting before it
  int64_t wall_origin_ns_ = 0;               // wall time at which session_origin_t_ns_ is due
  int64_t session_origin_t_ns_ = 0;
};

}  // namespace sculpt::sim
