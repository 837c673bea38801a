#include "sculpt/base/output_set.h"

#include <unistd.h>

#include <system_error>
#include <utility>

#include "sculpt/base/temp_files.h"

namespace sculpt {

OutputSet::~OutputSet() {
  if (!committed_) {
    for (const auto& [staged, target] : staged_) {
      std::error_code ignored;
      std::filesystem::remove(staged, ignored);
    }
  }
  for (const int slot : slots_)
    forget_temp_file(slot);
}

std::filesystem::path OutputSet::stage(const std::filesystem::path& target) {
  // The extension stays last: writers choose a format by it.
  // Appended piece by piece: gcc 12 warns (-Wrestrict, a known false
  // positive) on "." + std::string.
  std::string name = ".";
  name += target.stem().string();
  name += ".staged-" + std::to_string(::getpid()) + "-" + std::to_string(staged_.size());
  name += target.extension().string();
  std::filesystem::path staged = target.parent_path() / name;
  staged_.emplace_back(staged, target);
  slots_.push_back(remember_temp_file(staged.string()));
  return staged;
}

Error OutputSet::named(const Error& error) const {
  std::string message = error.message();
  for (const auto& [staged, target] : staged_) {
    const std::string from = staged.string(), to = target.string();
    for (size_t at = message.find(from); at != std::string::npos;
         at = message.find(from, at + to.size()))
      message.replace(at, from.size(), to);
  }
  return Error(message);
}

Status OutputSet::commit() {
  for (const auto& [staged, target] : staged_) {
    std::error_code ec;
    std::filesystem::rename(staged, target, ec);
    if (ec)
      return Error(target.string() + ": cannot move the finished file into place: " + ec.message());
  }
  committed_ = true;
  for (int& slot : slots_)
    forget_temp_file(std::exchange(slot, -1));
  return {};
}

}  // namespace sculpt
