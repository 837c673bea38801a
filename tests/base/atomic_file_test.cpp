#include "sculpt/base/atomic_file.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include "scratch_dir.h"
#include "sculpt/base/output_set.h"
#include "sculpt/base/temp_files.h"

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace sculpt::core {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

size_t files_in(const fs::path& dir) {
  return static_cast<size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

class AtomicFileTest : public ::testing::Test {
 protected:
  sculpt::test::ScratchDir scratch_;
  const fs::path& dir_ = scratch_.path();
};

TEST_F(AtomicFileTest, CommitReplacesTheTargetWhole) {
  const fs::path target = dir_ / "out.txt";
  std::ofstream(target) << "old";
  {
    AtomicFileWriter w(target);
    ASSERT_TRUE(w.ok());
    w.write("new ");
    EXPECT_EQ(slurp(target), "old");  // nothing visible before commit
    w.write("content");
    ASSERT_TRUE(w.commit().ok());
  }
  EXPECT_EQ(slurp(target), "new content");
  EXPECT_EQ(files_in(dir_), 1u);  // no temporary left behind
  // Readable like any new file (mkstemp alone would leave it 0600).
  const mode_t mask = ::umask(022);
  {
    AtomicFileWriter w(dir_ / "mode.txt");
    ASSERT_TRUE(w.commit().ok());
  }
  ::umask(mask);
  EXPECT_EQ(fs::status(dir_ / "mode.txt").permissions(),
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read |
                fs::perms::others_read);
}

TEST_F(AtomicFileTest, AbandonedWriteLeavesNothing) {
  const fs::path target = dir_ / "out.txt";
  std::ofstream(target) << "old";
  {
    AtomicFileWriter w(target);
    w.write("half");
  }
  EXPECT_EQ(slurp(target), "old");
  EXPECT_EQ(files_in(dir_), 1u);
  {
    AtomicFileWriter w(dir_ / "fresh.txt");
    w.write("half");
  }
  EXPECT_FALSE(fs::exists(dir_ / "fresh.txt"));
}

TEST_F(AtomicFileTest, UnwritableFolderIsReportedWithTheName) {
  AtomicFileWriter w(dir_ / "missing" / "out.txt");
  EXPECT_FALSE(w.ok());
  const Status st = w.commit();
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().message().find("missing/out.txt"), std::string::npos);
}

TEST_F(AtomicFileTest, ASignalDuringAWriteLeavesNoTemporary) {
  // The process dies of SIGTERM half way through an output (and with an
  // output set staged): the handler removes both temporaries first.
  // "fast" forks without re-running the test, so the child writes into
  // this test's own folder (the pool's idle threads hold no lock then).
  GTEST_FLAG_SET(death_test_style, "fast");
  const fs::path target = dir_ / "big.raw";
  EXPECT_EXIT(
      {
        remove_temp_files_on_signals();
        OutputSet outputs;
        const fs::path staged = outputs.stage(dir_ / "other.json");
        std::ofstream(staged) << "staged";
        AtomicFileWriter out(target);
        out.write(std::string(1 << 20, 'x'));
        std::raise(SIGTERM);
      },
      ::testing::KilledBySignal(SIGTERM), "");
  EXPECT_EQ(files_in(dir_), 0u);
}

TEST_F(AtomicFileTest, TemporariesOfKilledWritersAreRemovedByTheNextWriter) {
  const fs::path target = dir_ / "volume.nrrd";
  // A child that dies at once: its pid names a process that no longer runs.
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ASSERT_GT(dead, 0);
  ::waitpid(dead, nullptr, 0);
  const std::string dead_name = "volume.nrrd.tmp-" + std::to_string(dead) + "-Ab3dEf";
  const std::string live_name = "volume.nrrd.tmp-1-Gh5jKl";  // init: always running
  const std::string other_target = "other.nrrd.tmp-" + std::to_string(dead) + "-Mn7pQr";
  const std::string not_ours = "volume.nrrd.tmp-notapid";
  for (const std::string& name : {dead_name, live_name, other_target, not_ours})
    std::ofstream(dir_ / name) << "left over";
  {
    AtomicFileWriter w(target);
    ASSERT_TRUE(w.ok());
    w.write("whole");
    ASSERT_TRUE(w.commit().ok());
  }
  EXPECT_FALSE(fs::exists(dir_ / dead_name));    // the killed writer's: gone
  EXPECT_TRUE(fs::exists(dir_ / live_name));     // a running writer's: kept
  EXPECT_TRUE(fs::exists(dir_ / other_target));  // another target's: not ours to judge
  EXPECT_TRUE(fs::exists(dir_ / not_ours));      // not our naming: kept
  EXPECT_EQ(slurp(target), "whole");
}

}  // namespace
}  // namespace sculpt::core
