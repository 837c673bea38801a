#include "sculpt/base/input_file.h"

#include <string>

namespace sculpt {

Status check_input_file(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_type type = fs::status(path, ec).type();  // follows links
  const char* what = nullptr;
  switch (type) {
    case fs::file_type::directory:
      what = "is a directory";
      break;
    case fs::file_type::fifo:
      what = "is a FIFO (named pipe), not a file";
      break;
    case fs::file_type::character:
    case fs::file_type::block:
      what = "is a device, not a file";
      break;
    case fs::file_type::socket:
      what = "is a socket, not a file";
      break;
    default:  // a regular file, or missing: the reader names what it cannot open
      break;
  }
  if (what != nullptr) return Error(path.string() + ": " + what);
  return {};
}

}  // namespace sculpt
