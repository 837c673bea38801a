#include "sculpt/core/grid/cell_marks.h"

#include <algorithm>
#include <limits>

#include <glm/common.hpp>

namespace sculpt::core {
namespace {

// In-place prefix sums of a table of `n` values per axis, along each axis.
void sum_along_axes(std::vector<int32_t>& t, glm::ivec3 n) {
  const size_t sy = size_t(n.x), sz = size_t(n.x) * size_t(n.y);
  for (int z = 0; z < n.z; ++z)
    for (int y = 0; y < n.y; ++y) {
      int32_t* row = &t[size_t(z) * sz + size_t(y) * sy];
      for (int x = 1; x < n.x; ++x)
        row[x] += row[x - 1];
    }
  for (int z = 0; z < n.z; ++z)
    for (int y = 1; y < n.y; ++y) {
      int32_t* row = &t[size_t(z) * sz + size_t(y) * sy];
      const int32_t* before = row - sy;
      for (int x = 0; x < n.x; ++x)
        row[x] += before[x];
    }
  for (int z = 1; z < n.z; ++z) {
    int32_t* plane = &t[size_t(z) * sz];
    const int32_t* before = plane - sz;
    for (size_t i = 0; i < sz; ++i)
      plane[i] += before[i];
  }
}

}  // namespace

void CellMarks::reset(const Box& box) {
  box_ = box;
  cells_ = (box.size() + ((1 << kShift) - 1)) >> kShift;
  table_.assign(size_t(cells_.x + 1) * size_t(cells_.y + 1) * size_t(cells_.z + 1), 0);
  flags_.clear();
  bounds_ = Box{};
}

bool CellMarks::cell_range(const Box& voxels, glm::ivec3& lo, glm::ivec3& hi) const {
  const Box v = intersect(voxels, box_);
  if (v.empty()) return false;
  lo = cell_of(v.lo);
  hi = cell_of(v.hi - 1) + 1;
  return true;
}

void CellMarks::mark(const Box& voxels) {
  glm::ivec3 lo, hi;
  if (!cell_range(voxels, lo, hi)) return;
  // +1 at lo and alternating signs at the other corners: after the prefix
  // sums every cell of [lo, hi) holds one more.
  const size_t sy = size_t(cells_.x + 1), sz = sy * size_t(cells_.y + 1);
  int32_t* at = &table_[table_index(lo)];
  const size_t dx = size_t(hi.x - lo.x), dy = size_t(hi.y - lo.y) * sy,
               dz = size_t(hi.z - lo.z) * sz;
  at[0] += 1;
  at[dx] -= 1;
  at[dy] -= 1;
  at[dz] -= 1;
  at[dx + dy] += 1;
  at[dx + dz] += 1;
  at[dy + dz] += 1;
  at[dx + dy + dz] -= 1;
}

void CellMarks::finish() {
  const glm::ivec3 n = cells_ + 1;
  sum_along_axes(table_, n);
  flags_.resize(size_t(cells_.x) * size_t(cells_.y) * size_t(cells_.z));
  glm::ivec3 lo(std::numeric_limits<int>::max()), hi(std::numeric_limits<int>::min());
  uint8_t* flag = flags_.data();
  for (int z = 0; z < cells_.z; ++z)
    for (int y = 0; y < cells_.y; ++y) {
      const int32_t* count = &table_[table_index({0, y, z})];
      bool any_in_row = false;
      for (int x = 0; x < cells_.x; ++x, ++flag) {
        *flag = count[x] > 0;
        any_in_row |= *flag != 0;
      }
      if (!any_in_row) continue;
      const uint8_t* row = flag - cells_.x;
      int first = 0, last = cells_.x - 1;
      while (!row[first])
        ++first;
      while (!row[last])
        --last;
      lo = glm::min(lo, glm::ivec3(first, y, z));
      hi = glm::max(hi, glm::ivec3(last + 1, y + 1, z + 1));
    }
  bounds_ = lo.x > hi.x ? Box{}
                        : intersect(Box{box_.lo + (lo << kShift), box_.lo + (hi << kShift)}, box_);
  // The table becomes the summed marked cells before each cell (an extra
  // zero plane in front on each axis), so any() adds eight corners.
  std::fill(table_.begin(), table_.end(), 0);
  flag = flags_.data();
  for (int z = 0; z < cells_.z; ++z)
    for (int y = 0; y < cells_.y; ++y) {
      int32_t* out = &table_[table_index({1, y + 1, z + 1})];
      for (int x = 0; x < cells_.x; ++x)
        out[x] = *flag++;
    }
  sum_along_axes(table_, n);
}

bool CellMarks::any(const Box& voxels) const {
  glm::ivec3 lo, hi;
  if (!cell_range(voxels, lo, hi)) return false;
  int64_t sum = 0;
  for (int k = 0; k < 8; ++k) {
    const glm::ivec3 c{k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z};
    const int odd = (k & 1) + ((k >> 1) & 1) + ((k >> 2) & 1);
    sum += odd % 2 == 1 ? table_[table_index(c)] : -table_[table_index(c)];
  }
  return sum > 0;
}

}  // namespace sculpt::core
