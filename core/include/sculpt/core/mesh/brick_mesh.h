#pragma once
// A brick's part of a surface and the welding that joins the parts: the
// vertices on cell edges two bricks share carry a key naming the edge in the
// whole level, and welding merges vertices by key (the march makes them
// bit-identical on both sides, so no positions are compared).

#include <cstdint>
#include <vector>

#include "sculpt/core/mesh/mesh.h"

namespace sculpt::core {

/// The mesh of one brick's cells, before welding with its neighbours.
struct BrickMesh {
  Mesh mesh;
  /// A vertex on a cell edge shared with another brick's cells, and the key
  /// of that edge in the whole level. Welding merges vertices by key.
  struct Seam {
    uint32_t vertex = 0;
    uint64_t key = 0;
    friend bool operator==(const Seam&, const Seam&) = default;
  };
  /// The brick's seam vertices, by increasing vertex index. Most vertices
  /// are inside the brick, so only these carry a key.
  std::vector<Seam> seams;
  static constexpr uint64_t kNotSeam = ~uint64_t{0};

  bool empty() const { return mesh.triangles.empty(); }
  void clear() {
    mesh.positions.clear();
    mesh.normals.clear();
    mesh.triangles.clear();
    seams.clear();
  }
  friend bool operator==(const BrickMesh&, const BrickMesh&) = default;
};

/// Welds brick meshes (in the given order) into one mesh: vertices on shared
/// cell edges become one vertex.
Mesh weld_brick_meshes(const std::vector<const BrickMesh*>& bricks);

}  // namespace sculpt::core
