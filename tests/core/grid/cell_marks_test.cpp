#include "sculpt/core/grid/cell_marks.h"

#include <random>

#include <gtest/gtest.h>

namespace sculpt::core {
namespace {

TEST(CellMarks, AnswersLikeAVoxelByVoxelSearchOfTheMarkedCells) {
  const Box box{{-3, 5, 2}, {20, 22, 13}};  // odd sizes: the last cells are cut
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> x(-6, 23), y(2, 25), z(-1, 16);
  const auto random_box = [&] {
    glm::ivec3 a{x(rng), y(rng), z(rng)}, b{x(rng), y(rng), z(rng)};
    return Box{glm::min(a, b), glm::max(a, b) + 1};
  };
  for (int round = 0; round < 20; ++round) {
    CellMarks marks;
    marks.reset(box);
    // The reference: every voxel of a marked cell (cells of 2 from box.lo).
    std::vector<Box> marked;
    for (int i = 0; i < round % 4; ++i) {
      const Box b = random_box();
      marks.mark(b);
      marked.push_back(b);
    }
    marks.finish();
    const auto cell_marked = [&](glm::ivec3 v) {
      const glm::ivec3 c = (v - box.lo) >> 1;
      for (const Box& b : marked) {
        const Box cell = intersect(Box{box.lo + c * 2, box.lo + c * 2 + 2}, box);
        if (!intersect(cell, b).empty()) return true;
      }
      return false;
    };
    Box expected_bounds{glm::ivec3(1 << 20), glm::ivec3(-(1 << 20))};
    for (int vz = box.lo.z; vz < box.hi.z; ++vz)
      for (int vy = box.lo.y; vy < box.hi.y; ++vy)
        for (int vx = box.lo.x; vx < box.hi.x; ++vx) {
          const glm::ivec3 v{vx, vy, vz};
          ASSERT_EQ(marks.marked(v), cell_marked(v)) << vx << " " << vy << " " << vz;
          if (cell_marked(v)) {
            expected_bounds.lo = glm::min(expected_bounds.lo, v);
            expected_bounds.hi = glm::max(expected_bounds.hi, v + 1);
          }
        }
    EXPECT_EQ(marks.bounds(), expected_bounds.empty() ? Box{} : expected_bounds);
    for (int q = 0; q < 50; ++q) {
      const Box b = random_box();
      bool expected = false;
      const Box in = intersect(b, box);
      for (int vz = in.lo.z; vz < in.hi.z && !expected; ++vz)
        for (int vy = in.lo.y; vy < in.hi.y && !expected; ++vy)
          for (int vx = in.lo.x; vx < in.hi.x && !expected; ++vx)
            expected = cell_marked({vx, vy, vz});
      EXPECT_EQ(marks.any(b), expected);
    }
  }
}

TEST(CellMarks, NothingMarkedMeansNothingFound) {
  CellMarks marks;
  marks.reset(Box{{0, 0, 0}, {8, 8, 8}});
  marks.mark(Box{{20, 0, 0}, {30, 8, 8}});  // outside: clipped away
  marks.finish();
  EXPECT_TRUE(marks.bounds().empty());
  EXPECT_FALSE(marks.any(Box{{0, 0, 0}, {8, 8, 8}}));
}

}  // namespace
}  // namespace sculpt::core
