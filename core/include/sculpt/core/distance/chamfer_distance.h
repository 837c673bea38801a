#pragma once
// Chamfer distance transforms (Jones & Satherley §3.4): two raster passes of
// a distance matrix, forward with the half before the voxel and backward with
// the half after it (equation 4). Unsigned, voxel units.

#include <cstdint>

#include "sculpt/core/grid/dense_grid.h"

namespace sculpt::core {

enum class ChamferMask {
  /// 6 face neighbours, weight 1.
  kCity,
  /// 3x3x3 <3,4,5> (Borgefors 1986), divided by 3.
  k345,
  /// 5x5x5 quasi-Euclidean: every offset of the 5x5x5 neighbourhood that is
  /// not a multiple of a nearer one, weighted by its Euclidean length.
  k5x5x5,
};

/// Propagates `init` (distances at seed voxels, +infinity elsewhere) through
/// the grid with `mask`. Seeds keep their value unless a path is shorter.
DenseGrid<float> chamfer_distance(const DenseGrid<float>& init, ChamferMask mask);

}  // namespace sculpt::core
