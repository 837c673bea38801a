#pragma once
// A test volume drawn from a signed distance function: its density at each
// voxel centre as every shape's (core::density_from_distance, ramping over
// two voxels across the surface).

#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

#include "sculpt/core/shapes/analytic_shapes.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::test {

/// An n^3 volume whose density follows `distance` (signed, voxels; negative
/// inside) at each voxel centre.
template <class Distance>
core::Volume volume_of(int n, const Distance& distance) {
  return core::Volume::from_bricks(
      glm::ivec3(n), {}, [&](const core::Box& box, std::span<uint8_t> out) {
        size_t i = 0;
        for (int z = box.lo.z; z < box.hi.z; ++z)
          for (int y = box.lo.y; y < box.hi.y; ++y)
            for (int x = box.lo.x; x < box.hi.x; ++x)
              out[i++] = core::density_from_distance(distance(
                  glm::vec3(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z))));
      });
}

}  // namespace sculpt::test
