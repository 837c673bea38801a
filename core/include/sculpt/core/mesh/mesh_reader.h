#pragma once
// Triangle meshes from other programs, for `sculpt voxelize`: Wavefront OBJ
// (v and f records; polygons fan-triangulated; negative indices; v/vt/vn
// forms), PLY (ascii, binary little or big endian; vertex x y z as any
// numeric type; face vertex_indices lists) and STL (binary or ascii; equal
// corner positions welded into one vertex so the mesh is indexed).
// Coordinates are returned as stored; normals are not read.

#include <filesystem>

#include "sculpt/base/result.h"
#include "sculpt/core/mesh/mesh.h"

namespace sculpt::core {

/// Reads `path` by its extension (.obj, .ply, .stl, any case). Every error
/// names the file and, where it applies, the line or element.
Result<Mesh> read_mesh(const std::filesystem::path& path);

}  // namespace sculpt::core
