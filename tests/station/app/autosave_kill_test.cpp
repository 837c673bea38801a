// The station's autosave killed with SIGKILL at random moments: the autosave
// file is written to a temporary name and renamed into place, so what is
// left is always the last whole autosave, and it always loads. A forked
// child sculpts and autosaves as fast as it can (an autosave due at every
// tick of its clock); the parent waits for its first autosave, however slow
// the machine (a sanitizer build on a loaded one took over 600 ms), then
// kills it a random while later, mostly in the middle of a later one.

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <random>
#include <thread>

#include <gtest/gtest.h>

#include "scratch_dir.h"
#include "sculpt/station/app/station_controller.h"
#include "sculpt/station/project/project_file.h"

namespace sculpt::station {
namespace {

constexpr int64_t kMs = 1'000'000;

[[noreturn]] void sculpt_and_autosave_forever(const std::filesystem::path& folder) {
  ControllerOptions o;
  o.loop.volume_dims = glm::ivec3(96);
  o.loop.clay_margin = 16;
  o.project = folder / "p.sculpt";
  o.mesh_export = folder / "m.ply";
  o.recording = folder / "r.scs";
  o.normalizer_config_path = (folder / "input.conf").string();
  o.autosave_seconds = 0.001;
  StationController c(o);
  int64_t t = 0;
  for (float z = 0.0f;; z += 1.0f) {
    c.pointer_move({30.0f, 80.0f, 48.0f + std::fmod(z, 20.0f)}, t += kMs);
    c.pointer_down(t += kMs);
    for (int i = 0; i <= 10; ++i)
      c.pointer_move({30.0f + static_cast<float>(i), 80.0f, 48.0f}, t += kMs);
    c.pointer_up(t += kMs);
    c.update_mesh(t);
    c.tick(t += 10 * kMs);
  }
}

TEST(AutosaveKill, WhatIsLeftIsAWholeAutosaveOrNone) {
  test::ScratchDir dir;
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> wait_ms(0, 300);
  for (int run = 0; run < 6; ++run) {
    const std::filesystem::path folder = dir.path() / std::to_string(run);
    std::filesystem::create_directories(folder);
    const std::filesystem::path autosave = folder / "p.sculpt.autosave";
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) sculpt_and_autosave_forever(folder);
    // A bound only against a child that never autosaves (the test then
    // fails below): not a timing the test depends on.
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::minutes(2);
    while (!std::filesystem::exists(autosave) && std::chrono::steady_clock::now() < give_up)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::this_thread::sleep_for(std::chrono::milliseconds(wait_ms(rng)));
    ASSERT_EQ(::kill(pid, SIGKILL), 0);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFSIGNALED(status));
    ASSERT_TRUE(std::filesystem::exists(autosave)) << "run " << run << " never autosaved";
    const Result<Project> p = load_project(autosave);
    ASSERT_TRUE(p.ok()) << "run " << run << ": " << p.error().message();
    EXPECT_EQ(p->volume->dims(), glm::ivec3(96));
  }
}

}  // namespace
}  // namespace sculpt::station
