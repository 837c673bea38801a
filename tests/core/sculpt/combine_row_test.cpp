#include "sculpt/core/sculpt/combine_row.h"

#include <gtest/gtest.h>

#include <vector>

#include "sculpt/core/sculpt/sculptor.h"

namespace sculpt::core {
namespace {

// The vector kernel covers a row in 32-byte steps and blends the bytes past
// its end back: every row length, offset and strength must give the scalar
// loop's voxels and count, and leave the bytes around the row alone.
TEST(CombineRow, MatchesTheScalarLoopForEveryLengthAndStrength) {
  constexpr int kMax = 80;
  uint32_t s = 7;
  auto next = [&] {
    s = s * 1664525u + 1013904223u;
    return s >> 8;
  };
  std::vector<uint8_t> tool(kMax + 8 + kCombineRowSlack), material(tool.size());
  for (SculptMode mode :
       {SculptMode::kAdd, SculptMode::kSubtract, SculptMode::kUnion, SculptMode::kDifference}) {
    for (uint32_t q : {0u, 1u, 77u, 128u, 255u, 256u}) {
      for (int n = 0; n <= kMax; ++n) {
        for (int offset : {0, 3}) {
          for (size_t i = 0; i < tool.size(); ++i) {
            // Runs of 0 and 255 as in a real tool and material, and noise.
            const uint32_t r = next();
            tool[i] = static_cast<uint8_t>(r % 3 == 0 ? 0 : r % 3 == 1 ? 255 : r >> 4);
            material[i] = static_cast<uint8_t>(next() % 4 == 0 ? 255 : next() >> 3);
          }
          std::vector<uint8_t> want = material;
          const int64_t want_changed =
              combine_row_scalar(mode, want.data() + offset, tool.data() + offset, n, q);
          const int64_t changed =
              combine_row(mode, material.data() + offset, tool.data() + offset, n, q);
          ASSERT_EQ(material, want) << sculpt_mode_name(mode) << " q " << q << " n " << n;
          ASSERT_EQ(changed, want_changed) << sculpt_mode_name(mode) << " q " << q << " n " << n;
        }
      }
    }
  }
}

TEST(CombineRow, FullStrengthAddAndSubtractSaturate) {
  std::vector<uint8_t> m = {0, 100, 200, 255, 3};
  const std::vector<uint8_t> f = {255, 100, 100, 1, 0};
  m.resize(m.size() + kCombineRowSlack);
  std::vector<uint8_t> fs = f;
  fs.resize(m.size());
  EXPECT_EQ(combine_row(SculptMode::kAdd, m.data(), fs.data(), 5, 256), 3);
  EXPECT_EQ(std::vector<uint8_t>(m.begin(), m.begin() + 5),
            (std::vector<uint8_t>{255, 200, 255, 255, 3}));
  EXPECT_EQ(combine_row(SculptMode::kSubtract, m.data(), fs.data(), 5, 256), 4);
  EXPECT_EQ(std::vector<uint8_t>(m.begin(), m.begin() + 5),
            (std::vector<uint8_t>{0, 100, 155, 254, 3}));
}

}  // namespace
}  // namespace sculpt::core
