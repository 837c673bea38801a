#include "sculpt/core/volume/brick.h"

#include <algorithm>
#include <cstring>

namespace sculpt::core {

Brick::Brick(Brick&& other) noexcept
    : value_(other.value_),
      pyramid_(std::move(other.pyramid_)),
      shared_(other.shared_.exchange(false, std::memory_order_relaxed)) {}

Brick& Brick::operator=(Brick&& other) noexcept {
  if (this != &other) {
    value_ = other.value_;
    pyramid_ = std::move(other.pyramid_);
    shared_.store(other.shared_.exchange(false, std::memory_order_relaxed),
                  std::memory_order_relaxed);
  }
  return *this;
}

Brick::Brick(const Brick& other) : value_(other.value_), pyramid_(other.pyramid_) {
  if (pyramid_) {
    other.shared_.store(true, std::memory_order_relaxed);
    shared_.store(true, std::memory_order_relaxed);
  }
}

Brick& Brick::operator=(const Brick& other) {
  if (this != &other) *this = Brick(other);
  return *this;
}

WaveletPyramid& Brick::own_blank_pyramid(int edge, int levels) {
  if (!pyramid_ || shares_pyramid() || pyramid_->edge() != edge || pyramid_->levels() != levels) {
    pyramid_ = std::make_shared<WaveletPyramid>(edge, levels);
    shared_.store(false, std::memory_order_relaxed);
  }
  return *pyramid_;
}

bool Brick::holds_same_voxels(const Brick& other) const {
  if (is_uniform() || other.is_uniform())
    return is_uniform() && other.is_uniform() && value_ == other.value_;
  if (pyramid_ == other.pyramid_) return true;  // a copy not encoded since
  const WaveletPyramid& a = *pyramid_;
  const WaveletPyramid& b = *other.pyramid_;
  return a.edge() == b.edge() && a.levels() == b.levels() &&
         std::ranges::equal(a.coefficients(), b.coefficients());
}

void Brick::encode(std::span<const uint8_t> voxels, int edge, int levels) {
  // A brick away from the surface is all 0 or all 255: the common case, and the
  // reason memory grows with the sculpted surface rather than the bounding box.
  // No early exit: a branch-free OR over the brick vectorises, and a surface
  // brick often starts with thousands of equal voxels anyway.
  const uint8_t first = voxels[0];
  uint8_t differs = 0;
  for (const uint8_t v : voxels)
    differs |= static_cast<uint8_t>(v ^ first);
  if (differs == 0) {
    value_ = first;
    pyramid_.reset();
    shared_.store(false, std::memory_order_relaxed);
    return;
  }
  own_blank_pyramid(edge, levels).encode(voxels);
}

void Brick::encode_region(std::span<const uint8_t> voxels, int edge, int levels,
                          std::array<int, 3> lo, std::array<int, 3> hi) {
  if (!pyramid_ || pyramid_->edge() != edge || pyramid_->levels() != levels) {
    encode(voxels, edge, levels);  // uniform before: no coefficients to update
    return;
  }
  // A detailed brick rarely turns uniform under one dab: stop at the first
  // 64-byte block that is not all the first voxel (memcmp runs at the
  // widest vectors the CPU has, and the scan is the dab's cost otherwise).
  uint8_t pattern[64];
  std::memset(pattern, voxels[0], sizeof pattern);
  size_t i = 0;
  while (i + sizeof pattern <= voxels.size() &&
         std::memcmp(&voxels[i], pattern, sizeof pattern) == 0)
    i += sizeof pattern;
  const bool uniform =
      i >= voxels.size() || (i + sizeof pattern > voxels.size() &&
                             std::all_of(voxels.begin() + static_cast<std::ptrdiff_t>(i),
                                         voxels.end(), [&](uint8_t v) { return v == voxels[0]; }));
  if (uniform) {
    value_ = voxels[0];
    pyramid_.reset();
    shared_.store(false, std::memory_order_relaxed);
    return;
  }
  if (shares_pyramid()) {
    // Copy on write: the other holders keep the pyramid as it was.
    pyramid_ = std::make_shared<WaveletPyramid>(*pyramid_);
    shared_.store(false, std::memory_order_relaxed);
  }
  pyramid_->encode_region(voxels, lo, hi);
}

void Brick::extract_level(int level, std::span<uint8_t> out) const {
  if (pyramid_) {
    pyramid_->extract_level(level, out);
  } else {
    std::fill(out.begin(), out.end(), value_);
  }
}

}  // namespace sculpt::core
