#pragma once
// Runs the built `sculpt` executable the way a user does, for the
// command-line contract tests (exit codes, one-line errors, no partial output).

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace sculpt::station::test {

struct CommandResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Runs `build/bin/sculpt ARGS` (ARGS as shell words) and captures everything.
inline CommandResult run_sculpt(const std::string& args) {
  const std::filesystem::path err_file =
      std::filesystem::temp_directory_path() / ("sculpt_stderr_" + std::to_string(::getpid()));
  const std::string command =
      std::string(SCULPT_BINARY_DIR) + "/bin/sculpt " + args + " 2>" + err_file.string();
  CommandResult r;
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return r;
  char buffer[4096];
  for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;)
    r.out.append(buffer, n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = read_text(err_file);
  std::filesystem::remove(err_file);
  return r;
}

/// Number of lines in a message (a trailing newline does not count).
inline int line_count(const std::string& s) {
  int lines = 0;
  for (size_t i = 0; i < s.size(); ++i)
    lines += s[i] == '\n' || i + 1 == s.size();
  return lines;
}

}  // namespace sculpt::station::test
