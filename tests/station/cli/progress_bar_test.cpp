// Progress and Ctrl-C on the command line: plain lines at most every 10% when
// stderr is not a terminal, and SIGINT during `sculpt distance` or a .vdb
// `sculpt export` of a 256^3 volume ends it with one "cancelled" line, exit
// 130 and no output file.

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "run_sculpt.h"
#include "scratch_dir.h"
#include "sculpt/core/io/nrrd.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::station::test {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> lines_of(const std::string& s) {
  std::vector<std::string> lines;
  std::stringstream in(s);
  for (std::string line; std::getline(in, line);)
    lines.push_back(line);
  return lines;
}

TEST(ProgressBar, PlainLinesAtMostEveryTenthWhenNotATerminal) {
  sculpt::test::ScratchDir dir;
  ASSERT_TRUE(core::write_nrrd(dir.file("in.nrrd"), core::sphere_density(40)).ok());
  const CommandResult r =
      run_sculpt("distance " + dir.file("in.nrrd") + " -o " + dir.file("out.nrrd"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> lines = lines_of(r.err);
  ASSERT_GE(lines.size(), 2u) << r.err;
  EXPECT_LE(lines.size(), 11u) << r.err;
  EXPECT_EQ(lines.front(), "distance: 0%");
  EXPECT_EQ(lines.back(), "distance: 100%");
  int last = -1;
  for (const std::string& line : lines) {
    int percent = -1;
    ASSERT_EQ(std::sscanf(line.c_str(), "distance: %d%%", &percent), 1) << line;
    EXPECT_EQ(percent % 10, 0) << line;
    EXPECT_GT(percent, last) << line;
    last = percent;
  }
}

// Runs sculpt ARGS with stderr on a pipe it returns; stdout to /dev/null.
pid_t start_sculpt(const std::vector<std::string>& args, int* err_fd) {
  int fds[2];
  if (::pipe(fds) != 0) return -1;
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(fds[1], STDERR_FILENO);
    ::close(fds[0]);
    ::close(fds[1]);
    ::freopen("/dev/null", "w", stdout);
    const std::string binary = std::string(SCULPT_BINARY_DIR) + "/bin/sculpt";
    std::vector<char*> argv{const_cast<char*>(binary.c_str())};
    for (const std::string& a : args)
      argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(binary.c_str(), argv.data());
    ::_exit(127);
  }
  ::close(fds[1]);
  *err_fd = fds[0];
  return pid;
}

// Runs `sculpt COMMAND 256^3-sphere.nrrd -o OUTPUT ...`, sends SIGINT once
// its first progress line is out, and expects one "COMMAND: cancelled" line,
// exit 130 and nothing written (no output, no staged temporary).
void expect_ctrl_c_cancels(const std::string& command, const std::string& output) {
  sculpt::test::ScratchDir dir;
  ASSERT_TRUE(core::write_nrrd(dir.file("in.nrrd"), core::sphere_density(256)).ok());
  const fs::path out = dir.file(output);
  int err_fd = -1;
  const pid_t pid =
      start_sculpt({command, dir.file("in.nrrd"), "-o", out.string(), "--threads", "2"}, &err_fd);
  ASSERT_GT(pid, 0);
  // Read stderr until the first progress line is complete, then interrupt.
  std::string err;
  bool interrupted = false;
  char buffer[256];
  for (ssize_t n; (n = ::read(err_fd, buffer, sizeof buffer)) > 0;) {
    err.append(buffer, size_t(n));
    if (!interrupted && err.find('\n') != std::string::npos) {
      ASSERT_EQ(::kill(pid, SIGINT), 0);
      interrupted = true;
    }
  }
  ::close(err_fd);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(interrupted) << err;
  ASSERT_TRUE(WIFEXITED(status)) << err;
  EXPECT_EQ(WEXITSTATUS(status), 130) << err;
  // (append, not operator+: GCC 12 warns falsely of overlapping copies there.)
  const std::string cancelled = std::string(command).append(": cancelled");
  int cancelled_lines = 0;
  for (const std::string& line : lines_of(err))
    cancelled_lines += line == cancelled;
  EXPECT_EQ(cancelled_lines, 1) << err;
  EXPECT_EQ(lines_of(err).back(), cancelled) << err;
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(dir.path()))
    files.push_back(e.path().filename().string());
  EXPECT_EQ(files, std::vector<std::string>{"in.nrrd"});
}

TEST(ProgressBar, CtrlCCancelsDistanceWritingNothing) {
  expect_ctrl_c_cancels("distance", "out.nrrd");
}

// A .vdb export measures its level set first, with progress.
TEST(ProgressBar, CtrlCCancelsAVdbExportWritingNothing) {
  expect_ctrl_c_cancels("export", "out.vdb");
}

}  // namespace
}  // namespace sculpt::station::test
