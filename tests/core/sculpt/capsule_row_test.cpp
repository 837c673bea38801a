#include "sculpt/core/sculpt/capsule_row.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include <glm/geometric.hpp>

namespace sculpt::core {
namespace {

// The AVX2 kernel computes a brick row's fillings 8 at a time (skipping the
// groups already full) and raises the coverage in one 32-byte step: for
// segments in every direction, rows through, beside and past the capsule,
// every stretch [lo, hi) of the row and coverage of full and empty groups,
// runs of 0 and 255 and noise, it must give the scalar loop's coverage (the
// row and the bytes after it) and grown stretch; and so must it given the
// stretch inside radius - 1 to fill unmeasured.
TEST(CapsuleRow, GrowingMatchesTheScalarLoopForEveryStretch) {
  uint32_t s = 11;
  auto next = [&] {
    s = s * 1664525u + 1013904223u;
    return s >> 8;
  };
  auto uniform = [&](float lo, float hi) {
    return lo + (hi - lo) * static_cast<float>(next() % 65536) / 65535.0f;
  };
  int grown_rows = 0, kernel_rows = 0, rows_with_inside = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const glm::vec3 a(uniform(-8.0f, 40.0f), uniform(-4.0f, 4.0f), uniform(-4.0f, 4.0f));
    // Points, short and long segments, some along x.
    const float length = trial % 5 == 0 ? 0.0f : uniform(0.0f, 20.0f);
    glm::vec3 dir(uniform(-1.0f, 1.0f), uniform(-1.0f, 1.0f), uniform(-1.0f, 1.0f));
    if (trial % 7 == 0) dir = glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 ab = glm::length(dir) > 0.0f ? length * glm::normalize(dir) : glm::vec3(0.0f);
    const float ab2 = glm::dot(ab, ab);
    const float radius = uniform(1.0f, 14.0f);
    const float inner = std::max(0.0f, radius - 1.0f);
    const int x0 = 32 * static_cast<int>(next() % 3) - 32;
    const float apy = uniform(-radius - 2.0f, radius + 2.0f);
    const float apz = uniform(-radius - 2.0f, radius + 2.0f);
    const CapsuleRow row{a.x,
                         ab,
                         ab2 > 0.0f ? 1.0f / ab2 : 0.0f,
                         apy,
                         apz,
                         apy * ab.y + apz * ab.z,
                         radius,
                         inner * inner,
                         (radius + 1.0f) * (radius + 1.0f)};
    // The row's voxels at least a voxel inside radius - 1, found in double
    // precision (a capsule meets a row in one stretch): the stroke's spans
    // name such a stretch for the kernel to fill unmeasured.
    int in_lo = 32, in_hi = 0;
    for (int x = 0; x < 32; ++x) {
      const glm::dvec3 p(static_cast<double>(x0 + x) - static_cast<double>(a.x), apy, apz), d(ab);
      const double dd = glm::dot(d, d);
      const double t = dd > 0.0 ? std::clamp(glm::dot(p, d) / dd, 0.0, 1.0) : 0.0;
      if (glm::length(p - t * d) <= static_cast<double>(inner) - 1.0) {
        in_lo = std::min(in_lo, x);
        in_hi = x + 1;
      }
    }
    // Whole 8-voxel groups inside: the kernel fills those unmeasured.
    for (int g = 0; g < 4; ++g)
      if (8 * g >= in_lo && 8 * g + 8 <= in_hi) {
        ++rows_with_inside;
        break;
      }
    for (int lo = 0; lo < 32; lo += 1 + static_cast<int>(next() % 4)) {
      for (int hi = lo; hi <= 32; hi += 1 + static_cast<int>(next() % 5)) {
        // Per 8 voxels: filled fully (the kernel skips them), empty, runs of
        // 0 and 255, or noise.
        std::vector<uint8_t> cov(64);
        for (size_t g = 0; g < cov.size(); g += 8) {
          const uint32_t kind = next() % 4;
          for (size_t i = g; i < g + 8; ++i) {
            const uint32_t r = next();
            cov[i] = static_cast<uint8_t>(kind == 0   ? 255
                                          : kind == 1 ? 0
                                          : kind == 2 ? (r % 2 ? 255 : 0)
                                                      : r >> 5);
          }
        }
        std::vector<uint8_t> want = cov, fill(64), scratch(64);
        const GrownStretch w =
            grow_hard_capsule_row_scalar(row, x0, lo, hi, want.data(), fill.data());
        std::vector<uint8_t> cov_inside = cov;
        const GrownStretch g = grow_hard_capsule_row(row, x0, lo, hi, cov.data(), scratch.data());
        ASSERT_EQ(cov, want) << "trial " << trial << " lo " << lo << " hi " << hi;
        const GrownStretch gi =
            grow_hard_capsule_row(row, x0, lo, hi, cov_inside.data(), scratch.data(), in_lo, in_hi);
        ASSERT_EQ(cov_inside, want) << "inside, trial " << trial << " lo " << lo << " hi " << hi;
        ASSERT_EQ(gi.begin < gi.end, w.begin < w.end) << "inside, trial " << trial;
        if (w.begin < w.end) {
          ASSERT_EQ(gi.begin, w.begin) << "inside, trial " << trial;
          ASSERT_EQ(gi.end, w.end) << "inside, trial " << trial;
        }
        ASSERT_EQ(g.begin < g.end, w.begin < w.end) << "trial " << trial;
        if (w.begin < w.end) {
          ASSERT_EQ(g.begin, w.begin) << "trial " << trial << " lo " << lo << " hi " << hi;
          ASSERT_EQ(g.end, w.end) << "trial " << trial << " lo " << lo << " hi " << hi;
          ++grown_rows;
        }
        ++kernel_rows;
      }
    }
  }
  // Enough of both: rows the capsule raised, and rows it left alone.
  EXPECT_GT(grown_rows, kernel_rows / 10);
  EXPECT_LT(grown_rows, kernel_rows);
  EXPECT_GT(rows_with_inside, 10);  // and rows with groups filled unmeasured
}

}  // namespace
}  // namespace sculpt::core
