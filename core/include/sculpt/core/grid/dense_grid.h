#pragma once
// A plain dense 3D array, x fastest in memory (DESIGN.md §3). Used for
// whole-volume inputs and outputs: NRRD files, extracted levels of detail,
// distance fields.

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/core/grid/box.h"
#include "sculpt/core/grid/grid_index.h"

namespace sculpt::core {

template <class T>
class DenseGrid {
 public:
  DenseGrid() = default;
  /// A grid of `dims` voxels, every one set to `fill`.
  explicit DenseGrid(glm::ivec3 dims, T fill = T{})
      : dims_(dims), data_(static_cast<size_t>(voxel_count(dims)), fill) {
    assert(dims.x >= 0 && dims.y >= 0 && dims.z >= 0);
  }

  glm::ivec3 dims() const { return dims_; }
  size_t size() const { return data_.size(); }
  /// Linear index of voxel (x, y, z).
  size_t index(int x, int y, int z) const { return grid_index({x, y, z}, dims_); }
  bool in_bounds(int x, int y, int z) const {
    return x >= 0 && y >= 0 && z >= 0 && x < dims_.x && y < dims_.y && z < dims_.z;
  }

  T& at(int x, int y, int z) {
    assert(in_bounds(x, y, z));
    return data_[index(x, y, z)];
  }
  const T& at(int x, int y, int z) const {
    assert(in_bounds(x, y, z));
    return data_[index(x, y, z)];
  }
  T& operator[](size_t i) { return data_[i]; }
  const T& operator[](size_t i) const { return data_[i]; }

  T* data() { return data_.data(); }
  const T* data() const { return data_.data(); }
  std::vector<T>& values() { return data_; }
  const std::vector<T>& values() const { return data_; }

  friend bool operator==(const DenseGrid&, const DenseGrid&) = default;

 private:
  glm::ivec3 dims_{0};
  std::vector<T> data_;
};

}  // namespace sculpt::core
