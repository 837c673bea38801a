#include <cstdio>
#include <iostream>
#include <string>

#include "cli/commands.h"

namespace sculpt::station::cli {
namespace {

// At most this many bytes of a message are shown: a message quoting a
// hostile input (a header line of kilobytes) stays one readable line.
constexpr size_t kMaxMessageBytes = 300;

// The message as one printable line: control bytes (a newline from a quoted
// input, escape sequences) become \xNN, and a long one is cut with "...".
// Bytes of 0x80 and above pass (UTF-8 file names).
std::string printable(const std::string& message) {
  std::string out;
  for (const char c : message) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7F) {
      char escaped[5];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", u);
      out += escaped;
    } else {
      out += c;
    }
    if (out.size() >= kMaxMessageBytes) {
      out += "...";
      break;
    }
  }
  return out;
}

}  // namespace

int report(const Error& error) {
  std::cerr << "sculpt: " << printable(error.message()) << "\n";
  return 1;
}

}  // namespace sculpt::station::cli
