#pragma once
// Density volumes of shapes whose geometry is known exactly: the workloads of
// the benchmarks (../shared/bench/peers.py builds the identical inputs) and
// the reference shapes of the tests.
//
// Density from signed distance d (voxel units, negative inside):
//   clip(127.5 - 127.5 d, 0, 255), truncated to uint8,
// so the 127.5 iso-surface is the shape's surface and the ramp is 2 voxels wide.

#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

#include "sculpt/core/grid/box.h"
#include "sculpt/core/grid/dense_grid.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::core {

/// Density of a signed distance d in voxel units (see above).
uint8_t density_from_distance(float d);

/// The peers.py sphere: n^3 voxels, centre (n-1)/2, radius r_frac * n.
DenseGrid<uint8_t> sphere_density(int n, float r_frac = 0.35f);
/// The same sphere as a bricked volume, built brick by brick (no dense copy).
Volume sphere_volume(int n, float r_frac = 0.35f, const VolumeOptions& options = {});

/// A sphere of `radius` at `centre` (voxel units) written into `box` of `out`
/// (x fastest, box.size()): the brick-fill form used by Volume::from_bricks.
void fill_sphere(const Box& box, glm::vec3 centre, float radius, std::span<uint8_t> out);

/// A torus around the z axis through `centre`: major radius R, minor radius r.
DenseGrid<uint8_t> torus_density(glm::ivec3 dims, glm::vec3 centre, float major_radius,
                                 float minor_radius);
/// An axis-aligned box with corners lo and hi (voxel units).
DenseGrid<uint8_t> box_density(glm::ivec3 dims, glm::vec3 lo, glm::vec3 hi);

}  // namespace sculpt::core
