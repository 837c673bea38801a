#include "sculpt/hal/force/hand_script.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <string>

#include "scratch_dir.h"

namespace sculpt::hal {
namespace {

TEST(HandScript, ParsesEveryStatementAndInterpolatesThePath) {
  const auto script = parse_hand_script(
      "sculpt-hand 1   # a comment\n"
      "\n"
      "grip 0.8 6\n"
      "at 0 0 10 0\n"
      "at 1.0 0 -10 0\t# down through the wall\n"
      "buttons 0.5 3\n"
      "buttons 0.75 0\n"
      "unplug 2\n",
      "hand.txt");
  ASSERT_TRUE(script.ok()) << script.error().message();
  EXPECT_FLOAT_EQ(script->stiffness_n_per_mm, 0.8f);
  EXPECT_FLOAT_EQ(script->damping_ns_per_m, 6.0f);
  EXPECT_EQ(script->target_at(-1.0), glm::vec3(0.0f, 10.0f, 0.0f));
  EXPECT_EQ(script->target_at(0.25), glm::vec3(0.0f, 5.0f, 0.0f));
  EXPECT_EQ(script->target_at(5.0), glm::vec3(0.0f, -10.0f, 0.0f));
  EXPECT_EQ(script->buttons_at(0.4), 0u);
  EXPECT_EQ(script->buttons_at(0.6), 3u);
  EXPECT_EQ(script->buttons_at(0.8), 0u);
  EXPECT_DOUBLE_EQ(script->unplug_s, 2.0);
  EXPECT_DOUBLE_EQ(script->end_s(), 2.0);
}

TEST(HandScript, BadScriptsSayWhichLineAndWhatIsWrong) {
  const auto error = [](const char* text) {
    const auto script = parse_hand_script(text, "h.txt");
    EXPECT_FALSE(script.ok()) << text;
    return script.ok() ? std::string() : script.error().message();
  };
  EXPECT_EQ(error(""), "h.txt: empty; expected the header 'sculpt-hand 1'");
  EXPECT_EQ(error("sculpt-hand 2\n"), "h.txt:1: expected the header 'sculpt-hand 1'");
  EXPECT_EQ(error("sculpt-hand 1\n"), "h.txt: no 'at' line: the hand goes nowhere");
  EXPECT_EQ(error("sculpt-hand 1\nat 0 1 2\n"), "h.txt:2: at takes a time (s) and x y z (mm)");
  EXPECT_EQ(error("sculpt-hand 1\nat 0 1 2 nan\n"), "h.txt:2: 'nan' is not a finite number");
  EXPECT_EQ(error("sculpt-hand 1\nat 1 0 0 0\nat 0.5 0 0 0\n"), "h.txt:3: time goes backwards");
  EXPECT_EQ(error("sculpt-hand 1\nat 0 0 0 5000\n"), "h.txt:2: position beyond 1000 mm");
  EXPECT_EQ(error("sculpt-hand 1\nat 0 0 0 0\nbuttons 0 1.5\n"),
            "h.txt:3: buttons takes a time (s) and a mask (an integer of 32 bits)");
  EXPECT_EQ(error("sculpt-hand 1\nat 0 0 0 0\ngrip -1 0\n"),
            "h.txt:3: grip takes a stiffness in [0, 100] N/mm and a damping in [0, 1000] N·s/m");
  EXPECT_EQ(error("sculpt-hand 1\nat 0 0 0 0\nfly 1\n"),
            "h.txt:3: unknown statement 'fly' (grip, at, buttons, unplug)");
  EXPECT_EQ(error("sculpt-hand 1\nat 0 0 0 0\nunplug -1\n"),
            "h.txt:3: unplug takes a time in [0, 86400] s");
}

TEST(HandScript, AMissingFileIsAnError) {
  const auto script = read_hand_script("/nonexistent/hand.txt");
  ASSERT_FALSE(script.ok());
  EXPECT_EQ(script.error().message(), "/nonexistent/hand.txt: cannot open");
}

// `--haptic sim-arm:FILE` names its script in the device string: a FIFO
// there is named, not waited for (the open would block until a writer came).
TEST(HandScript, AFifoIsNamedNotWaitedFor) {
  const test::ScratchDir dir;
  const std::string fifo = dir.file("hand.txt");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto script = read_hand_script(fifo);
  ASSERT_FALSE(script.ok());
  EXPECT_EQ(script.error().message(), fifo + ": is a FIFO (named pipe), not a file");
}

}  // namespace
}  // namespace sculpt::hal
