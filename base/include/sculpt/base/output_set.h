#pragma once
// The outputs of one command, which appear all or none (DESIGN.md §7): each
// is first written whole (through its usual writer) under a staged name in
// its target's folder; commit() renames them all over their targets. A set
// destroyed before commit() removes what it staged, so a failure at the
// third output leaves none of the first two behind.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "sculpt/base/result.h"

namespace sculpt {

class OutputSet {
 public:
  OutputSet() = default;
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  /// Where to write `target` now: a hidden name beside it with the same
  /// extension, unique to this process and set.
  std::filesystem::path stage(const std::filesystem::path& target);
  /// An error a writer gave for a staged path, told with the user's path.
  Error named(const Error& error) const;
  /// Renames every staged file over its target, in the order staged.
  Status commit();

 private:
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> staged_;  // staged, target
  std::vector<int> slots_;  // temp_files.h: staged files a signal removes
  bool committed_ = false;
};

}  // namespace sculpt
