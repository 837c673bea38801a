#pragma once
// Opens a session file in either form: binary (.scs, recognised by its magic)
// or JSON Lines text (anything else).

#include <filesystem>

#include "sculpt/base/result.h"
#include "sculpt/sim/session/session.h"
#include "sculpt/sim/session/session_file.h"

namespace sculpt::station {

/// A damaged tail of a binary file is dropped; `info` says what was lost.
Result<sim::Session> load_session(const std::filesystem::path& path,
                                  sim::SessionReadInfo* info = nullptr);

}  // namespace sculpt::station
