#include "sculpt/core/volume/brick.h"

#include <algorithm>
#include <cstring>

namespace sculpt::core {

Brick::Brick(const Brick& other)
    : value_(other.value_),
      pyramid_(other.pyramid_ ? std::make_unique<WaveletPyramid>(*other.pyramid_) : nullptr) {}

Brick& Brick::operator=(const Brick& other) {
  if (this != &other) *this = Brick(other);
  return *this;
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
    return;
  }
  if (!pyramid_ || pyramid_->edge() != edge || pyramid_->levels() != levels) {
    pyramid_ = std::make_unique<WaveletPyramid>(edge, levels);
  }
  pyramid_->encode(voxels);
}

void Brick::extract_level(int level, std::span<uint8_t> out) const {
  if (pyramid_) {
    pyramid_->extract_level(level, out);
  } else {
    std::fill(out.begin(), out.end(), value_);
  }
}

}  // namespace sculpt::core
