#pragma once
// Temporary files that a SIGINT, SIGTERM or SIGHUP must not leave behind (a
// killed `sculpt replay --volume` once left a 1.3 GB OUT.tmp-XXXXXX). The
// atomic writers and output sets list their temporaries here while they
// exist; the handler removes them (unlink is async-signal-safe) and then
// dies of the signal as it would have.

#include <string>

namespace sculpt {

/// Lists `path` until forget_temp_file(); returns its slot, or -1 when the
/// list (64 entries) is full (the file is then only removed the usual way).
int remember_temp_file(const std::string& path);
void forget_temp_file(int slot);

/// Installs the handlers (once; later calls do nothing). The `sculpt`
/// executable calls it first thing.
void remove_temp_files_on_signals();

}  // namespace sculpt
