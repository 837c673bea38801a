#pragma once
// What the volume commands share: the --threads option, registered one way;
// the field output of the distance commands (a float32 signed distance or
// the uint8 density it encloses); and the mapping of other voxel types to
// density (--window, --data-iso).

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "sculpt/base/result.h"
#include "sculpt/core/grid/dense_grid.h"
#include "sculpt/core/io/nrrd.h"

namespace sculpt::station::cli {

/// How a volume of other voxels than uint8 (CT data is 16-bit) becomes
/// density: --window LO,HI, or --data-iso V.
struct DensityOptions {
  std::vector<double> window;  ///< LO, HI when given
  double data_iso = std::numeric_limits<double>::quiet_NaN();
};
/// Registers --window and --data-iso on `command`.
void add_density_options(CLI::App* command, DensityOptions& options);
/// The window the options ask for for the volume at `path` (none: uint8
/// voxels are density as they are).
Result<std::optional<core::DensityWindow>> density_window(const DensityOptions& options,
                                                          const std::string& path);

/// --threads N: 0 (all cores) to 1024.
CLI::Option* add_threads_option(CLI::App* command, int& threads);

/// Writes `field` (voxel units, negative inside) to the NRRD `path`: as
/// float32 signed distance when `as_distance`, else as uint8 density.
Status write_field(const std::string& path, const core::DenseGrid<float>& field, bool as_distance);
/// How write_field() wrote it, for the "wrote" line.
const char* field_kind(bool as_distance);

}  // namespace sculpt::station::cli
