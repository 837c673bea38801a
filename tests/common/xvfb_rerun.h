#pragma once
// Tests that need an OpenGL window run themselves again, without a display,
// in a process of their own under xvfb-run (Mesa's software OpenGL, as in CI).

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "scratch_dir.h"

namespace sculpt::test {

/// Runs the current test again under xvfb-run and expects it to pass;
/// false when there is no xvfb-run (the test is then skipped).
inline bool rerun_under_xvfb(const ScratchDir& dir) {
  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) return false;
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  // Mesa keeps some of its allocations to the end: not this test's leaks.
  const std::string command =
      "ASAN_OPTIONS=\"${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0\" xvfb-run -a -f '" +
      (dir.path() / "xvfb-auth").string() + "' -s '-screen 0 640x480x24' '" + self +
      "' --gtest_filter=" + info->test_suite_name() + "." + info->name() + " > '" +
      (dir.path() / "out.txt").string() + "' 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream out(dir.path() / "out.txt");
  std::stringstream text;
  text << out.rdbuf();
  std::printf("%s", text.str().c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "under xvfb-run";
  return true;
}

}  // namespace sculpt::test
