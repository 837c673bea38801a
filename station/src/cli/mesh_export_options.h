#pragma once
// What every mesh export shares (`sculpt mesh`, `export`, `replay --mesh`):
// --simplify RATIO and --max-error VOXELS (core/mesh/mesh_simplify.h), the
// print check --check with --voxel-mm (core/mesh/print_check.h) and --ascii,
// registered one way, applied in one order (simplify, then check, so the
// mesh checked is the mesh written) and reported one way.
//
// Repair is not offered: a mesh from a volume is closed by construction
// unless the material touches the block's faces, and the fix for that is in
// the volume (`sculpt close`, a larger block), not in hole filling after the
// fact. A mesh that fails the check is refused, never patched silently.

#include <string>

#include <CLI/CLI.hpp>

#include "sculpt/base/result.h"
#include "sculpt/core/mesh/mesh.h"
#include "sculpt/core/mesh/mesh_io.h"
#include "sculpt/core/mesh/mesh_simplify.h"
#include "sculpt/core/mesh/print_check.h"

namespace sculpt::station::cli {

struct MeshExportOptions {
  core::MeshSimplifyOptions simplify;
  bool check = false;     ///< the print check: refuse a mesh that would not print
  double voxel_mm = 1.0;  ///< for the check's volume and size: millimetres per voxel
  bool ascii = false;     ///< ASCII instead of binary PLY
};

/// Registers --simplify and --max-error on `command`.
void add_simplify_options(CLI::App* command, core::MeshSimplifyOptions& options);
/// Registers --simplify, --max-error, --check, --voxel-mm and --ascii.
void add_mesh_export_options(CLI::App* command, MeshExportOptions& options);

/// The format `output`'s extension names; an error when it names none, or
/// --ascii is asked for another format than PLY.
Result<core::MeshFormat> mesh_export_format(const std::string& output,
                                            const MeshExportOptions& options);

/// `mesh` simplified as the options ask (as it was when they ask nothing),
/// with one line saying what it became: triangles before and after, and the
/// measured error.
core::Mesh simplify_for_export(core::Mesh mesh, const core::MeshSimplifyOptions& options);

/// The mesh to write: simplified as asked, then, with --check, checked (the
/// report printed on stdout). A mesh that would not print is an error
/// "<name>: <what stops it printing>".
Result<core::Mesh> prepare_mesh_export(core::Mesh mesh, const MeshExportOptions& options,
                                       const std::string& name);

/// What stops `check`'s mesh printing, in a few words.
std::string print_problems(const core::PrintCheck& check);
/// The print check's report on stdout.
void print_check_report(const core::PrintCheck& check, double voxel_mm);

}  // namespace sculpt::station::cli
