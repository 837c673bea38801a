#pragma once
// The check every reader of a file from outside makes before opening it:
// the path must not name something that is no file. A folder would be read
// as an empty or malformed file; a FIFO (named pipe) or a terminal blocks
// the open or the read until another program writes, so the station would
// hang where it should say what is wrong.

#include <filesystem>

#include "sculpt/base/result.h"

namespace sculpt {

/// An error "PATH: is a directory" (or a FIFO, a device, a socket) when
/// `path` exists and is not a regular file, or a symbolic link to one; no
/// error otherwise. A missing file is left to the reader, which names it
/// when it cannot open it.
Status check_input_file(const std::filesystem::path& path);

}  // namespace sculpt
