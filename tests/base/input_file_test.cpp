#include "sculpt/base/input_file.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "scratch_dir.h"

namespace sculpt {
namespace {

namespace fs = std::filesystem;

std::string refusal(const fs::path& path) {
  const Status s = check_input_file(path);
  return s ? std::string() : s.error().message();
}

TEST(InputFile, AFileOrAMissingPathPassesAndWhatIsNoFileIsNamed) {
  const test::ScratchDir dir;
  const fs::path file = dir.path() / "session.scs";
  std::ofstream(file) << "x";
  EXPECT_EQ(refusal(file), "");
  EXPECT_EQ(refusal(dir.path() / "missing.scs"), "");  // the reader says it cannot open it

  EXPECT_EQ(refusal(dir.path()), dir.path().string() + ": is a directory");
  const fs::path fifo = dir.path() / "pipe.scs";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(refusal(fifo), fifo.string() + ": is a FIFO (named pipe), not a file");
  EXPECT_EQ(refusal("/dev/null"), "/dev/null: is a device, not a file");

  // A link is what it points to.
  fs::create_symlink(file, dir.path() / "to_file.scs");
  fs::create_symlink(fifo, dir.path() / "to_fifo.scs");
  EXPECT_EQ(refusal(dir.path() / "to_file.scs"), "");
  EXPECT_EQ(refusal(dir.path() / "to_fifo.scs"),
            (dir.path() / "to_fifo.scs").string() + ": is a FIFO (named pipe), not a file");
}

}  // namespace
}  // namespace sculpt
