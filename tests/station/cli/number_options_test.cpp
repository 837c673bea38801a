// Numeric command-line options refuse NaN and infinities (CLI11's own range
// checks let NaN through: every comparison with it is false), as bad input:
// one line, exit 1.

#include <gtest/gtest.h>

#include "run_sculpt.h"

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

}  // namespace
}  // namespace sculpt::station::test
