#pragma once
// A session replayed as fast as it goes, for the tests that look at what it
// sculpts, not at its pace (at the recording's pace a replay of the demo
// takes the demo's whole length).

#include <string>

#include "sculpt/station/app/session_replay.h"

namespace sculpt::test {

inline Result<station::ReplayResult> replay_fast(const sim::Session& session,
                                                 const std::string& name,
                                                 station::StationLoop& loop) {
  station::ReplayOptions fast;
  fast.fast = true;
  return station::replay_session(session, name, loop, fast);
}

}  // namespace sculpt::test
