// Numeric command-line options refuse NaN and infinities (CLI11's own range
// checks let NaN through: every comparison with it is false), as bad input:
// one line, exit 1.

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <string>

#include "run_sculpt.h"
#include "scratch_dir.h"

namespace sculpt::station::test {
namespace {

TEST(NumberOptions, NanAndInfinityAreRefusedWithTheOptionNamed) {
  const struct {
    const char* args;
    const char* option;
  } cases[] = {{"replay s.scs --speed nan", "--speed"},
               {"replay s.scs --speed inf", "--speed"},
               {"mesh v.nrrd -o m.ply --iso nan", "--iso"},
               {"record --seconds nan -o r.scs", "--seconds"},
               {"offset v.nrrd -o o.nrrd --by nan", "--by"},
               {"close v.nrrd -o c.nrrd --radius -inf", "--radius"}};
  for (const auto& [args, option] : cases) {
    const CommandResult r = run_sculpt(args);
    EXPECT_EQ(r.exit_code, 1) << args;
    EXPECT_EQ(line_count(r.err), 1) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("sculpt: " + std::string(option) + ": value ", 0), 0u)
        << args << ": " << r.err;
    EXPECT_NE(r.err.find("is not a number"), std::string::npos) << args << ": " << r.err;
  }
}

// Reproducer from the hardening review: a folder given as an input file was
// opened and reported as an empty session, "not a NRRD file" or an unknown
// mesh extension, or (run --open) ignored.
TEST(InputPaths, AFolderGivenAsAnInputFileIsNamedAsOne) {
  const std::string folder = SCULPT_TEST_DATA_DIR;
  // Each command with the folder where it reads its input.
  const std::string commands[] = {"replay " + folder,
                                  "wavelet " + folder,
                                  "mesh " + folder + " -o /nonexistent/m.ply",
                                  "session to-text " + folder + " -o /nonexistent/s.jsonl",
                                  "contours " + folder + " -o /nonexistent/c.nrrd",
                                  "voxelize " + folder + " --size 32 -o /nonexistent/v.nrrd",
                                  "nurbs tessellate " + folder + " -o /nonexistent/t.obj",
                                  "rotate " + folder + " --euler 1,2,3 -o /nonexistent/r.nrrd"};
  for (const std::string& command : commands) {
    const CommandResult r = run_sculpt(command);
    EXPECT_EQ(r.exit_code, 1) << command;
    EXPECT_EQ(line_count(r.err), 1) << command << r.err;
    EXPECT_NE(r.err.find(folder + ": is a directory"), std::string::npos) << command << r.err;
  }
}

// A FIFO (named pipe) given where a file is read blocked the open until a
// writer came: the command hung. Each place a path is read from, the command
// line's inputs and the paths inside device strings, now names it instead
// (a force device's hand script: hand_script_test.cpp, as it needs a display here).
TEST(InputPaths, AFifoGivenAsAnInputFileIsNamedNotWaitedFor) {
  const sculpt::test::ScratchDir dir;
  const std::string fifo = dir.file("pipe.scs");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string commands[] = {"replay " + fifo, "mesh " + fifo + " -o /nonexistent/m.ply",
                                  "run --open " + fifo + " --frames 2",
                                  "run --device sim:" + fifo + " --frames 2",
                                  "record --device sim:" + fifo + " -o /nonexistent/r.scs"};
  for (const std::string& command : commands) {
    const CommandResult r = run_sculpt(command);
    EXPECT_EQ(r.exit_code, 1) << command;
    EXPECT_EQ(line_count(r.err), 1) << command << r.err;
    EXPECT_NE(r.err.find(fifo + ": is a FIFO (named pipe), not a file"), std::string::npos)
        << command << r.err;
  }
}

}  // namespace
}  // namespace sculpt::station::test
