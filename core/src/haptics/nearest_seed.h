#pragma once
// The distance patch's search for each value's nearest seed (see
// distance_patch.h): every seed is offered to the values within `reach`
// of it, and a value keeps the nearest.
//
// A value holds one 32-bit key: the squared distance in fixed point (14
// bits up to reach^2), above the seed's number (16 bits). The nearest seed is then the smallest
// key, ties go to the lower number whatever order seeds are offered in, and an offer is one
// unsigned minimum over a row: half the memory of a distance and a number
// kept apart, and no compare and blend.

#include <cstddef>
#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

#include "sculpt/core/grid/box.h"

namespace sculpt::core {

/// How many seeds one search can tell apart: numbers 1 to kMaxSeeds.
inline constexpr size_t kMaxSeeds = (size_t{1} << 16) - 1;
/// Values a row of the search's table holds beyond the region's own (the
/// sixteen-lane steps run past a row's end into them).
inline constexpr int kRowPadding = 16;

/// The key every value starts from: no seed within reach. An offer at
/// reach or beyond never replaces it.
uint32_t unreached_key(int reach);
/// The index (into the points offered) of the seed a key holds; -1 when
/// unreached.
inline int32_t seed_of_key(uint32_t key) {
  return int32_t(key & uint32_t(kMaxSeeds)) - 1;
}

/// Offers `points` (at most kMaxSeeds, in the order that breaks ties) to
/// the values of `clip`, a z slab of `region`, laid out x fastest in `keys`
/// with rows `stride` = region width + kRowPadding apart. Distances tie
/// within reach^2 / 16383 voxel^2 (0.0015 for reach 5).
void offer_seeds(std::span<const glm::vec3> points, const Box& region, const Box& clip,
                 size_t stride, int reach, uint32_t* keys);

}  // namespace sculpt::core
