#pragma once
// Mesh files for other 3D programs (DESIGN.md §7): PLY (binary little-endian
// or ASCII, positions and normals), Wavefront OBJ (positions, normals) and
// binary STL (facet normals, vertices repeated per triangle as STL demands).
// Coordinates are voxel units. Files appear whole or not at all
// (AtomicFileWriter).

#include <filesystem>

#include "sculpt/base/result.h"
#include "sculpt/core/mesh/mesh.h"

namespace sculpt::core {

/// kGlb: binary glTF 2.0, one mesh of one triangle primitive with POSITION
/// (and NORMAL when the mesh has them) as float VEC3 and uint32 indices, in
/// one buffer; what Blender, game engines and web viewers open.
enum class MeshFormat { kPlyBinary, kPlyAscii, kObj, kStl, kGlb };

/// The format `path`'s extension names (.ply, .obj, .stl, .glb, any case);
/// PLY is binary unless `ascii_ply`. The error names the path and the
/// extension.
Result<MeshFormat> mesh_format_for(const std::filesystem::path& path, bool ascii_ply = false);

/// Writes `mesh` as `format`. The error names the path.
Status write_mesh(const std::filesystem::path& path, const Mesh& mesh, MeshFormat format);

}  // namespace sculpt::core
