#pragma once
// The state a recording starts from. A session holds device reports and
// station commands, not a volume: a recording started on an opened project
// or after some sculpting has the station's state at that moment saved as a
// project beside it (SESSION.start.sculpt), and replays restore it before
// playing, so the recording replays onto what the user was working on.

#include <filesystem>

#include "sculpt/base/result.h"
#include "sculpt/station/app/station_loop.h"

namespace sculpt::station {

/// SESSION.start.sculpt for SESSION.
std::filesystem::path session_start_path(const std::filesystem::path& session);

/// If `session` has a start project beside it, restores it into `loop`
/// (true); false when there is none; an error when it is there but cannot
/// be read (its message names the file).
Result<bool> restore_session_start(const std::filesystem::path& session, StationLoop& loop);

}  // namespace sculpt::station
