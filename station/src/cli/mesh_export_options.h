#pragma once
// What every mesh export shares: --simplify RATIO and --max-error VOXELS
// (core/mesh/mesh_simplify.h), registered one way and reported one way.

#include <CLI/CLI.hpp>

#include "sculpt/core/mesh/mesh.h"
#include "sculpt/core/mesh/mesh_simplify.h"

namespace sculpt::station::cli {

/// Registers --simplify and --max-error on `command`.
void add_simplify_options(CLI::App* command, core::MeshSimplifyOptions& options);

/// `mesh` simplified as the options ask (as it was when they ask nothing),
/// with one line saying what it became: triangles before and after, and the
/// measured error.
core::Mesh simplify_for_export(core::Mesh mesh, const core::MeshSimplifyOptions& options);

}  // namespace sculpt::station::cli
