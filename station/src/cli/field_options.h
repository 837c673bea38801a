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
#include "sculpt/core/volume/volume.h"

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

/// `path`'s extension in lower case, with its dot (".vdb"), or "".
std::string lower_extension(const std::string& path);
/// Whether `path`'s extension names a volume file (.nrrd, .vdb, any case).
bool is_volume_file_name(const std::string& path);

/// The volume at `path` (.nrrd, .vdb) as density, mapped as `density`
/// asks: what every command that reads a volume to mesh or convert it reads.
Result<core::Volume> read_volume_input(const std::string& path, const DensityOptions& density,
                                       const core::VolumeOptions& options);
/// Writes level `lod` of `volume` to `path` (.nrrd, or .vdb with its level
/// set, with a progress bar and Ctrl-C as cancel, lines named `command`) and
/// says so on stdout. Returns the command's exit code: 0; 1 after one error
/// line naming the path; kCancelledExit, nothing written.
int write_volume_level(const std::string& command, const std::string& path,
                       const core::Volume& volume, int lod);

/// --threads N: 0 (all cores) to 1024.
CLI::Option* add_threads_option(CLI::App* command, int& threads);

/// Writes `field` (voxel units, negative inside) to the NRRD `path`: as
/// float32 signed distance when `as_distance`, else as uint8 density.
Status write_field(const std::string& path, const core::DenseGrid<float>& field, bool as_distance);
/// How write_field() wrote it, for the "wrote" line.
const char* field_kind(bool as_distance);

}  // namespace sculpt::station::cli
