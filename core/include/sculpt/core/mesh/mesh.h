#pragma once
// An indexed triangle mesh and the checks a closed surface must pass.
//
// Positions are in level-0 voxel units (voxel (x, y, z) at x, y, z); normals
// are unit vectors pointing out of the material (toward lower density);
// triangles are counter-clockwise seen from outside.

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace sculpt::core {

struct Mesh {
  /// #V positions, voxel units.
  std::vector<glm::vec3> positions;
  /// #V unit normals (may be empty for meshes read from elsewhere).
  std::vector<glm::vec3> normals;
  /// #F triangles, each three indices into positions.
  std::vector<glm::uvec3> triangles;

  friend bool operator==(const Mesh&, const Mesh&) = default;
};

/// What the edges and vertices of a mesh say about its surface.
struct MeshTopology {
  int64_t vertices = 0;  ///< vertices used by at least one triangle
  int64_t edges = 0;     ///< undirected edges
  int64_t faces = 0;
  int64_t boundary_edges = 0;        ///< edges in one triangle (holes, cracks)
  int64_t nonmanifold_edges = 0;     ///< edges in three or more triangles
  int64_t misoriented_edges = 0;     ///< edges walked the same way by two triangles
  int64_t nonmanifold_vertices = 0;  ///< vertices whose triangles do not form one fan
  int64_t degenerate_triangles = 0;  ///< triangles repeating an index

  /// V - E + F: 2 for a sphere, 0 for a torus (per closed component).
  int64_t euler_characteristic() const { return vertices - edges + faces; }
  /// Every edge in exactly two triangles, walked once each way.
  bool closed() const {
    return boundary_edges == 0 && nonmanifold_edges == 0 && misoriented_edges == 0;
  }
  bool manifold() const {
    return closed() && nonmanifold_vertices == 0 && degenerate_triangles == 0;
  }
};

/// Counts edges, boundary and non-manifold elements (indices below
/// positions.size(), asserted) in time linear in the mesh's size. `border`,
/// when given, is set to whether each vertex is an end of a boundary edge
/// (a hole's or an open surface's border), from the same grouping of edges.
MeshTopology check_topology(const Mesh& mesh, std::vector<bool>* border = nullptr);

/// The axis-aligned box of the positions (lo > hi in every axis when empty).
struct MeshBounds {
  glm::vec3 lo{0.0f};
  glm::vec3 hi{0.0f};
};
MeshBounds mesh_bounds(const Mesh& mesh);
/// Total triangle area, square voxel units.
double surface_area(const Mesh& mesh);
/// Signed enclosed volume (divergence theorem), cubic voxel units: positive
/// when the triangles face outward.
double enclosed_volume(const Mesh& mesh);
/// Number of connected components (by shared vertices).
int64_t component_count(const Mesh& mesh);

}  // namespace sculpt::core
