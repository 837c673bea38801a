#pragma once
// What the distance-field commands (close, offset, voxelize, contours,
// distance, mesh) share: the --threads option, registered one way, and the
// field output: a float32 signed distance or the uint8 density it encloses.

#include <string>

#include <CLI/CLI.hpp>

#include "sculpt/base/result.h"
#include "sculpt/core/grid/dense_grid.h"

namespace sculpt::station::cli {

/// --threads N: 0 (all cores) to 1024.
CLI::Option* add_threads_option(CLI::App* command, int& threads);

/// Writes `field` (voxel units, negative inside) to the NRRD `path`: as
/// float32 signed distance when `as_distance`, else as uint8 density.
Status write_field(const std::string& path, const core::DenseGrid<float>& field, bool as_distance);
/// How write_field() wrote it, for the "wrote" line.
const char* field_kind(bool as_distance);

}  // namespace sculpt::station::cli
