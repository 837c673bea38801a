#pragma once
// Meshes read by their file name: `.glb` is binary glTF (glb_file.h), .obj,
// .ply and .stl the mesh reader (mesh/mesh_reader.h). Every command that
// reads a mesh goes through here, so a format added here works for all of
// them (`voxelize`, `import`, `mesh --check`).

#include <filesystem>

#include "sculpt/base/result.h"
#include "sculpt/core/mesh/mesh.h"

namespace sculpt::core {

/// Whether `path`'s extension names a mesh file read here (.obj, .ply,
/// .stl, .glb; any case).
bool is_mesh_file_name(const std::filesystem::path& path);

/// Reads `path` by its extension; every error names the file.
Result<Mesh> read_mesh_file(const std::filesystem::path& path);

/// Millimetres per unit of the file's coordinates when the file does not
/// say: 1000 for glTF (its unit is the metre), 1 for the others (STL and
/// OBJ from CAD and printing tools are millimetres by convention).
double mesh_unit_mm(const std::filesystem::path& path);

}  // namespace sculpt::core
