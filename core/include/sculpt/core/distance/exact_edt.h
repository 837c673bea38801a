#pragma once
// Exact Euclidean distance transform in linear time (Felzenszwalb &
// Huttenlocher, "Distance transforms of sampled functions", ToC 2012): one
// 1D pass per axis, each the lower envelope of parabolas. Not in Jones &
// Satherley (2001); it computes exactly what their naive §3.1 method does, in
// O(n) instead of O(n^2), and is the basis of the hybrid `exact --init shell`.
//
// Seeds are the voxels of `mask` equal to `seed_value`. Distances are in voxel
// units between voxel centres; +infinity when there is no seed at all.
// Multithreaded with parallel_for (threads = 0: default_threads()); the result
// does not depend on the thread count.

#include <cstdint>

#include "sculpt/core/grid/dense_grid.h"

namespace sculpt::core {

/// Squared distance from every voxel to the nearest seed (voxel units^2).
DenseGrid<float> squared_edt(const DenseGrid<uint8_t>& mask, uint8_t seed_value, int threads = 0);

/// Distance from every voxel to the nearest seed (voxel units). With
/// seed_value 0 on a 0/1 mask this is scipy.ndimage.distance_transform_edt.
DenseGrid<float> exact_edt(const DenseGrid<uint8_t>& mask, uint8_t seed_value, int threads = 0);

struct FeatureTransform {
  /// Squared distance to the nearest seed, voxel units^2 (+inf: no seed).
  DenseGrid<float> distance_squared;
  /// Linear index (DenseGrid::index) of that seed; -1 when there is none.
  /// Among equally near seeds the choice is fixed (the same for any thread
  /// count).
  DenseGrid<int32_t> nearest;
};

/// The distance and the nearest seed of every voxel.
FeatureTransform feature_transform(const DenseGrid<uint8_t>& mask, uint8_t seed_value,
                                   int threads = 0);

}  // namespace sculpt::core
