// `sculpt record` killed with SIGKILL at random moments: what is left always
// loads, and it is the device's input from the start, in order, with no
// record damaged (a record is appended with one write(2) every 10 ms, so the
// kernel holds everything but the last few milliseconds; the tail a reader
// drops is at most one record cut by the kill).

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <random>
#include <thread>

#include <gtest/gtest.h>

#include "scratch_dir.h"
#include "sculpt/sim/session/session_file.h"

namespace sculpt::station::test {
namespace {

namespace fs = std::filesystem;

// Starts `sculpt record` on a sim device playing `session`, output to `out`.
pid_t start_recording(const fs::path& session, const fs::path& out) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const std::string binary = std::string(SCULPT_BINARY_DIR) + "/bin/sculpt";
    const std::string device = "sim:" + session.string();
    ::freopen("/dev/null", "w", stdout);
    ::execl(binary.c_str(), binary.c_str(), "record", "--device", device.c_str(), "-o", out.c_str(),
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return pid;
}

TEST(RecordKill, WhatIsLeftAlwaysLoadsAndIsThePrefixOfTheInput) {
  const fs::path source = fs::path(SCULPT_SESSIONS_DIR) / "demo.scs";
  auto original = sim::read_session_file(source);
  ASSERT_TRUE(original.ok()) << original.error().message();
  std::vector<sim::SessionRecord> device_records;
  for (const sim::SessionRecord& r : original->records) {
    if (r.kind == sim::SessionRecord::Kind::kEvent) device_records.push_back(r);
  }
  sculpt::test::ScratchDir dir;
  std::mt19937 rng(2026);
  std::uniform_int_distribution<int> wait_ms(0, 400);
  for (int run = 0; run < 6; ++run) {
    const fs::path out = dir.path() / ("r" + std::to_string(run) + ".scs");
    const pid_t pid = start_recording(source, out);
    ASSERT_GT(pid, 0);
    // Until the first records are in (bounded: a hang fails the test).
    std::error_code ec;
    for (int i = 0; i < 10000 && !(fs::exists(out, ec) && fs::file_size(out, ec) > 512); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::this_thread::sleep_for(std::chrono::milliseconds(wait_ms(rng)));
    ASSERT_EQ(::kill(pid, SIGKILL), 0);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFSIGNALED(status)) << "the recorder ended before the kill (run " << run << ")";

    sim::SessionReadInfo info;
    auto left = sim::read_session_file(out, &info);
    ASSERT_TRUE(left.ok()) << left.error().message();
    ASSERT_GT(left->records.size(), 0u);
    EXPECT_LT(info.bytes_lost, 256) << "at most one record cut by the kill: " << info.warning;
    size_t at = 0;
    for (const sim::SessionRecord& r : left->records) {
      if (r.kind != sim::SessionRecord::Kind::kEvent) continue;
      ASSERT_LT(at, device_records.size());
      const hal::RawEvent& got = r.event;
      const hal::RawEvent& want = device_records[at++].event;
      ASSERT_EQ(got.kind, want.kind) << "record " << at;
      ASSERT_TRUE(std::equal(got.bytes().begin(), got.bytes().end(), want.bytes().begin(),
                             want.bytes().end()))
          << "record " << at << " is not the device's";
    }
    EXPECT_GT(at, 0u);
  }
}

}  // namespace
}  // namespace sculpt::station::test
