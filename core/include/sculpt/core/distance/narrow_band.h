#pragma once
// The exact signed distance to a triangle mesh in a narrow band around it
// (the workload of OpenVDB's meshToLevelSet), stored sparsely in bricks.
// Signs as MeshDistance gives them (mesh_distance.h).

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/core/distance/mesh_distance.h"
#include "sculpt/core/grid/dense_grid.h"
#include "sculpt/core/grid/grid_index.h"

namespace sculpt::core {

struct NarrowBandOptions {
  /// Half width of the band, voxel units: voxels nearer than this get exact
  /// distances.
  float band = 3.0f;
  int threads = 0;
};

/// The exact signed distances of the voxels within the band, stored sparsely
/// in bricks of kBrick^3 voxels: only the bricks the band can reach hold
/// values (a few percent of a 256^3 box for a closed surface), as OpenVDB's
/// meshToLevelSet returns a sparse grid. Voxel (x, y, z) lies in brick
/// (x, y, z) / kBrick, x fastest both among bricks and within a brick.
struct NarrowBand {
  static constexpr int kBrick = 8;
  static constexpr int kBrickVoxels = kBrick * kBrick * kBrick;

  glm::ivec3 dims{0};
  /// Bricks per axis: ceil(dims / kBrick).
  glm::ivec3 bricks{0};
  /// Per brick: its slot in `distance` and `triangle`, or -1 when no
  /// triangle's band reaches it (a brick with a slot may still hold only
  /// voxels outside the band).
  std::vector<int32_t> slot;
  /// Per slot: the brick it holds (index into `slot`).
  std::vector<int32_t> slot_brick;
  /// kBrickVoxels values per slot: the signed distance inside the band,
  /// +infinity outside it (and past the grid's end in edge bricks).
  std::vector<float> distance;
  /// The triangle holding each in-band voxel's closest point, -1 outside.
  std::vector<int32_t> triangle;

  /// Index into `distance` and `triangle` of voxel (x, y, z) of the grid, or
  /// -1 when its brick has no slot.
  int64_t value_index(int x, int y, int z) const {
    const int32_t s =
        slot[size_t((int64_t(z / kBrick) * bricks.y + y / kBrick) * bricks.x + x / kBrick)];
    if (s < 0) return -1;
    return int64_t(s) * kBrickVoxels + ((z % kBrick) * kBrick + y % kBrick) * kBrick + x % kBrick;
  }
  /// Signed distance of voxel (x, y, z) of the grid: +infinity outside the band.
  float distance_at(int x, int y, int z) const;
  /// Closest triangle of voxel (x, y, z), -1 outside the band.
  int32_t triangle_at(int x, int y, int z) const;
  /// The grid voxel of value `k` of slot `s`.
  glm::ivec3 voxel(int32_t s, int k) const {
    const int32_t b = slot_brick[size_t(s)];
    return grid_position(b, bricks) * kBrick + grid_position(k, glm::ivec3(kBrick));
  }
  /// The band as a dense grid (+infinity outside it).
  DenseGrid<float> dense_distance(int threads = 0) const;
  /// The closest triangles as a dense grid (-1 outside the band).
  DenseGrid<int32_t> dense_triangle(int threads = 0) const;
};

/// Exact signed distances of every voxel of a `dims` grid within the band
/// around `mesh` (mesh positions in the grid's voxel coordinates). The
/// result does not depend on the number of threads.
NarrowBand mesh_narrow_band(const MeshDistance& mesh, glm::ivec3 dims,
                            const NarrowBandOptions& options = {});

/// For tests: false makes mesh_narrow_band use its 4-lane baseline kernel
/// even where the CPU has AVX2 (both give the same band). Returns the
/// previous setting.
bool use_avx2_band_kernel(bool enabled);

}  // namespace sculpt::core
