#pragma once
// Hypertexture on distance fields (Jones & Satherley §4.3, after Perlin &
// Hoffert 1989): outside the surface, within the soft region 0 <= D <= delta,
// the density follows 1 - D'/delta where D' is the distance pushed by fractal
// noise, so the iso-surface grows a noisy skin up to delta voxels thick.
// Inside (D <= 0) nothing changes; beyond delta nothing changes; densities
// only grow (max with the old value), so the brush never carves.

#include <cstdint>

#include <glm/vec3.hpp>

#include "sculpt/core/grid/box.h"
#include "sculpt/core/grid/dense_grid.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::core {

struct HypertextureOptions {
  /// Width delta of the soft region, voxels.
  float width_vox = 4.0f;
  /// Noise frequency, cycles per voxel.
  float frequency = 0.15f;
  /// Octaves of the turbulence (sum of |noise| at doubling frequencies).
  int octaves = 4;
  /// How far the noise moves the soft region, as a fraction of delta (0..1).
  float amplitude = 0.8f;
  uint32_t seed = 1;
  int threads = 0;
};

/// Turbulence in [0, 1) at p (voxel units): the noise of the skin.
float hypertexture_turbulence(glm::vec3 p, const HypertextureOptions& options);

/// Bakes the skin into the voxels of `box` of a dense density grid.
/// Returns the number of voxels whose density changed.
int64_t bake_hypertexture(DenseGrid<uint8_t>& density, const Box& box,
                          const HypertextureOptions& options = {});

/// The brush form: bakes into `box` (level-0 voxels) of a bricked volume,
/// reading a margin of delta + 2 voxels around it so distances near the box
/// faces see the surface beyond them. Only bricks touching the box are
/// re-encoded. Returns the number of voxels changed.
int64_t bake_hypertexture(Volume& volume, const Box& box, const HypertextureOptions& options = {});

}  // namespace sculpt::core
