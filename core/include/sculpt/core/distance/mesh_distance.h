#pragma once
// Signed distance to a closed triangle mesh (Jones & Satherley §3.2 for
// meshes): the exact point-to-triangle distance, signed by the angle-weighted
// pseudonormal of the closest feature (Baerentzen & Aanaes, IEEE TVCG 11(3)
// 2005), which is correct for any closed, consistently oriented manifold,
// with no ray casting. Positions and distances in voxel units (mesh.h);
// negative inside; triangles counter-clockwise seen from outside.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/base/result.h"
#include "sculpt/core/grid/dense_grid.h"
#include "sculpt/core/mesh/mesh.h"
#include "sculpt/core/util/progress.h"

namespace sculpt::core {

class MeshDistance {
 public:
  /// Precomputes face, edge and vertex pseudonormals. O(F log F).
  explicit MeshDistance(const Mesh& mesh);

  const Mesh& mesh() const { return mesh_; }
  /// Signed distance from p to triangle t's plane side, given that t holds
  /// the closest point of the whole mesh to p.
  float signed_distance_to(glm::vec3 p, uint32_t t) const;
  /// Signed distance from p to the mesh by testing every triangle (O(F)).
  float signed_distance_brute(glm::vec3 p) const;

 private:
  const Mesh& mesh_;
  std::vector<glm::vec3> face_normal_;    // unit, per triangle
  std::vector<glm::vec3> edge_normal_;    // 3 per triangle: ab, bc, ca
  std::vector<glm::vec3> vertex_normal_;  // per vertex, angle-weighted
};

/// The signed distance of every voxel: exact in a band of 2 voxels, beyond it
/// the distance to the closest triangle of the nearest band voxel (found by
/// an exact feature transform) with that voxel's sign. `progress` (optional,
/// progress.h): a cancelled call returns a field to discard.
DenseGrid<float> mesh_signed_distance(const MeshDistance& mesh, glm::ivec3 dims, int threads = 0,
                                      Progress* progress = nullptr);

/// How `voxelize_mesh` placed the mesh: grid = mesh * scale + offset.
struct VoxelizeMapping {
  float scale = 1.0f;
  glm::vec3 offset{0.0f};
};

/// The smallest longest side of a mesh that can be fitted (its units).
inline constexpr float kMinMeshExtent = 1e-20f;
/// The mapping that centres the mesh's bounding box in an n^3 grid, its
/// longest side spanning n - 1 - 2 * margin voxels; an error when the mesh
/// is too small or too far out for float arithmetic to place it.
Result<VoxelizeMapping> fit_mesh_to_grid(const Mesh& mesh, int n, float margin);
/// A copy of `mesh` with positions mapped.
Mesh transform_mesh(const Mesh& mesh, const VoxelizeMapping& mapping);

}  // namespace sculpt::core
