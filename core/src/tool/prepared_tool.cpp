// PreparedTool: a reference tool made ready for rotation (tool_rotation.h).
// Everything the rotation kernels would otherwise test or recompute per
// sample is settled here once per tool: the zero padding that removes bounds
// tests, the reach and core radii that bound what must be sampled, and the
// per-cell tables of the two trilinear kernels (on first use: a tool that is
// never rotated, the ball brush's sphere, never pays for them).

#include "sculpt/core/tool/tool_rotation.h"

#include "sculpt/core/util/parallel_for.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace sculpt::core {

namespace {

// A row's voxels are compared eight at a time (a word against `value` in
// every byte), then one by one where a word differs: a big ball's rows are
// long runs of 0 and 255, and a byte at a time was most of preparing it.
uint64_t in_every_byte(uint8_t value) {
  return 0x0101010101010101ull * value;
}

// The first x in [from, to) whose voxel is not `value`, else -1.
int first_other(const uint8_t* row, int from, int to, uint8_t value) {
  const uint64_t same = in_every_byte(value);
  int x = from;
  for (uint64_t w; x + 8 <= to; x += 8) {
    std::memcpy(&w, row + x, sizeof w);
    if (w != same) break;
  }
  for (; x < to; ++x)
    if (row[x] != value) return x;
  return -1;
}

// The last x in [from, to) whose voxel is not `value`, else -1.
int last_other(const uint8_t* row, int from, int to, uint8_t value) {
  const uint64_t same = in_every_byte(value);
  int x = to;
  for (uint64_t w; x - 8 >= from; x -= 8) {
    std::memcpy(&w, row + x - 8, sizeof w);
    if (w != same) break;
  }
  for (; x > from; --x)
    if (row[x - 1] != value) return x - 1;
  return -1;
}

}  // namespace

PreparedTool::PreparedTool(Tool tool) : tool_(std::move(tool)) {
  const glm::ivec3 d = tool_.density.dims();
  const glm::ivec3 pd = d + 2 * kPad;
  padded_dims_ = pd;
  const size_t count = static_cast<size_t>(voxel_count(pd));
  // Slack after the grid, for reads wider than a byte.
  padded_.assign(count + 4, 0);
  const size_t px = pd.x;
  const size_t pxy = px * pd.y;
  // The core value: the voxel nearest the pivot's; no core if that is outside.
  const glm::ivec3 centre(glm::floor(tool_.pivot + 0.5f));
  const bool centred = tool_.density.in_bounds(centre.x, centre.y, centre.z);
  const uint8_t u = centred ? tool_.density.at(centre.x, centre.y, centre.z) : 0;
  // A sample at t reads voxels w with |t_i - w_i| <= m on every axis (m = 0.5
  // nearest, < 1 trilinear): it can be non-zero only within
  // |w - pivot| + m per axis of a non-zero voxel w, and reads only u closer
  // than |w - pivot| - m per axis to every voxel w != u. Per axis, not
  // sqrt(3) m along the radius: a thinner shell left to sample.
  constexpr double kMargin[2] = {0.5, 1.0};
  double reach2[2] = {0.0, 0.0};
  double other2[2] = {centred ? 1e300 : 0.0, centred ? 1e300 : 0.0};
  const glm::dvec3 pivot(tool_.pivot);
  if (u != 0) {
    // Outside the grid reads 0: the layers at -1 and d on each axis.
    for (int i = 0; i < 3; ++i) {
      const double gap = std::min(pivot[i] + 1.0, d[i] - pivot[i]);
      for (int k = 0; k < 2; ++k) {
        const double g = std::max(0.0, gap - kMargin[k]);
        other2[k] = std::min(other2[k], g * g);
      }
    }
  }
  // Per row only a few voxels can settle the radii: along x, |x - pivot.x|
  // is largest at the row's first and last non-zero voxels (the reach) and
  // smallest at the voxels other than u nearest the pivot on either side
  // (the core). The same sums of the same voxels as testing them all, at a
  // byte compare per voxel (a big tool has millions: 72 ms at 205^3 before).
  // Each slice settles its own radii (maxima and minima, so the slices'
  // order does not matter) and copies its rows: a big tool's slices run on
  // every core (the bust's 110-voxel ball, 11 million voxels, while the next
  // dab waits).
  struct Radii {
    double reach2[2], other2[2];
  };
  const Radii start{{reach2[0], reach2[1]}, {other2[0], other2[1]}};
  std::vector<Radii> slices(static_cast<size_t>(d.z), start);
  auto settle = [&](Radii& r2, int x, int y, int z, uint8_t v) {
    const glm::dvec3 r = glm::abs(glm::dvec3(x, y, z) - pivot);
    for (int k = 0; k < 2; ++k) {
      if (v != 0) {
        const glm::dvec3 far = r + kMargin[k];
        r2.reach2[k] = std::max(r2.reach2[k], glm::dot(far, far));
      }
      if (v != u) {
        const glm::dvec3 near = glm::max(r - kMargin[k], 0.0);
        r2.other2[k] = std::min(r2.other2[k], glm::dot(near, near));
      }
    }
  };
  // Voxels at or left of this are "left of the pivot" (closer from below).
  const int split = static_cast<int>(std::floor(pivot.x));
  constexpr int kSerialSlices = 64;
  parallel_for(
      d.z,
      [&](int64_t slice) {
        const int z = static_cast<int>(slice);
        Radii& r2 = slices[static_cast<size_t>(slice)];
        for (int y = 0; y < d.y; ++y) {
          const uint8_t* row = &tool_.density.at(0, y, z);
          std::copy(row, row + d.x, &padded_[(z + kPad) * pxy + (y + kPad) * px + kPad]);
          const int left_end = std::clamp(split + 1, 0, d.x);  // [0, left_end): left of the pivot
          const int first = first_other(row, 0, d.x, 0);
          const int last = last_other(row, 0, d.x, 0);
          const int below = last_other(row, 0, left_end, u);
          const int above = first_other(row, left_end, d.x, u);
          for (int x : {first, last, below, above})
            if (x >= 0) settle(r2, x, y, z, row[x]);
        }
      },
      d.z > kSerialSlices ? 0 : 1);
  for (const Radii& r2 : slices)
    for (int k = 0; k < 2; ++k) {
      reach2[k] = std::max(reach2[k], r2.reach2[k]);
      other2[k] = std::min(other2[k], r2.other2[k]);
    }
  for (int k = 0; k < 2; ++k) {
    reach_vox_[k] = static_cast<float>(std::sqrt(reach2[k]));
    core_radius_vox_[k] = centred ? static_cast<float>(std::sqrt(other2[k])) : 0.0f;
  }
  core_value_ = u;
}

void PreparedTool::build_cell_tables() const {
  const glm::ivec3 pd = padded_dims_;
  const size_t count = static_cast<size_t>(voxel_count(pd));
  const size_t px = pd.x;
  const size_t pxy = px * pd.y;
  // Cells whose 8 corners are equal: their trilinear sample is that value
  // whatever the weights. The last layer has no +1 neighbours and is never
  // sampled (samples floor to at most dims + 2).
  cells_.reset(new uint16_t[count]);
  corners_.reset(new uint64_t[count]);
  // Slices are independent: a big tool's tables are a hundred megabytes,
  // written once each (a small one's are done before another thread would
  // wake).
  constexpr int kSerialSlices = 64;
  parallel_for(
      pd.z,
      [&](int64_t slice) {
        const int z = static_cast<int>(slice);
        for (int y = 0; y < pd.y; ++y)
          for (int x = 0; x < pd.x; ++x) {
            const size_t i = z * pxy + y * px + x;
            if (z + 1 == pd.z || y + 1 == pd.y || x + 1 == pd.x) {
              cells_[i] = 0;  // the last layer: never sampled
              corners_[i] = 0;
              continue;
            }
            const uint8_t* p = &padded_[i];
            const uint8_t v = p[0];
            const bool uniform = p[1] == v && p[px] == v && p[px + 1] == v && p[pxy] == v &&
                                 p[pxy + 1] == v && p[pxy + px] == v && p[pxy + px + 1] == v;
            cells_[i] = uniform ? static_cast<uint16_t>(0x100 | v) : uint16_t{0};
            uint64_t c = 0;
            // y varies fastest, then x, then z (see corners()).
            const size_t offsets[8] = {0, px, 1, px + 1, pxy, pxy + px, pxy + 1, pxy + px + 1};
            for (int k = 0; k < 8; ++k)
              c |= static_cast<uint64_t>(p[offsets[k]]) << (8 * k);
            corners_[i] = c;
          }
      },
      pd.z > kSerialSlices ? 0 : 1);
}

}  // namespace sculpt::core
