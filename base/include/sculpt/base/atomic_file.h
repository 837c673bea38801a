#pragma once
// Output files that appear whole or not at all (DESIGN.md §7): bytes go to a
// temporary file beside the target, which is renamed over it on commit(). A
// writer destroyed without commit() removes the temporary, so a failure or a
// crash never leaves a partial output under the user's name. The temporary
// is TARGET.tmp-PID-XXXXXX; one that a killed process left (no handler runs
// on SIGKILL) is removed by the next writer of the same target.

#include <cstdio>
#include <filesystem>
#include <string>

#include "sculpt/base/result.h"

namespace sculpt {

class AtomicFileWriter {
 public:
  /// Opens a temporary file in the target's folder. Check ok() before writing.
  explicit AtomicFileWriter(std::filesystem::path target);
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

  /// Whether the temporary file is open; if not, error() says why.
  bool ok() const { return file_ != nullptr && error_.empty(); }
  Error error() const { return Error(target_.string() + ": " + error_); }

  /// Appends bytes; a failure is remembered and reported by commit().
  void write(const void* data, size_t size);
  void write(const std::string& text) { write(text.data(), text.size()); }

  /// Flushes, syncs and renames the temporary file over the target.
  Status commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temp_;
  std::FILE* file_ = nullptr;
  std::string error_;
  bool committed_ = false;
  int temp_slot_ = -1;  // temp_files.h: removed if a signal ends the process
};

}  // namespace sculpt
