#include "sculpt/base/output_set.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "scratch_dir.h"
#include "sculpt/base/atomic_file.h"

namespace sculpt::core {
namespace {

namespace fs = std::filesystem;

size_t files_in(const fs::path& dir) {
  return static_cast<size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

Status write_text(const fs::path& path, const std::string& text) {
  AtomicFileWriter out(path);
  out.write(text);
  return out.commit();
}

TEST(OutputSet, AllAppearOnCommitWithTheirExtensions) {
  sculpt::test::ScratchDir scratch;
  const fs::path dir = scratch.path();
  OutputSet outputs;
  const fs::path a = outputs.stage(dir / "a.ply"), b = outputs.stage(dir / "b.json");
  EXPECT_EQ(a.extension(), ".ply");  // writers choose a format by it
  ASSERT_TRUE(write_text(a, "one").ok());
  ASSERT_TRUE(write_text(b, "two").ok());
  EXPECT_FALSE(fs::exists(dir / "a.ply"));
  ASSERT_TRUE(outputs.commit().ok());
  EXPECT_TRUE(fs::exists(dir / "a.ply"));
  EXPECT_TRUE(fs::exists(dir / "b.json"));
  EXPECT_EQ(files_in(dir), 2u);
}

TEST(OutputSet, AFailureLeavesNoneOfThemAndNamesTheUsersPath) {
  sculpt::test::ScratchDir scratch;
  const fs::path dir = scratch.path();
  std::ofstream(dir / "a.ply") << "the old a";
  Error error("");
  {
    OutputSet outputs;
    ASSERT_TRUE(write_text(outputs.stage(dir / "a.ply"), "new a").ok());
    const Status st = write_text(outputs.stage(dir / "missing" / "b.json"), "b");
    ASSERT_FALSE(st.ok());
    error = outputs.named(st.error());
  }
  EXPECT_EQ(error.message().rfind((dir / "missing" / "b.json").string() + ":", 0), 0u)
      << error.message();
  std::ifstream in(dir / "a.ply");
  const std::string a((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(a, "the old a");
  EXPECT_EQ(files_in(dir), 1u);  // nothing staged is left behind
}

}  // namespace
}  // namespace sculpt::core
