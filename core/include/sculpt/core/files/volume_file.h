#pragma once
// Volumes read and written by their file name: `.vdb` is OpenVDB
// (vdb_file.h), anything else NRRD (io/nrrd.h). Every command that reads or
// writes a volume goes through here, so a format added here works for all of
// them (tool files, `stamp`, `mesh`, `wavelet`, the distance commands).
//
// A .vdb density is read from its "density" grid; a file with only a level set
// becomes density as a distance field does (density_from_distance(): the
// 127.5 surface at the zero level, a 2-voxel ramp). A density written as .vdb
// also gets its "surface" level set (the exact distance to its sub-voxel
// surface, signed_distance.h), unless it has no surface (empty or solid).

#include <filesystem>

#include "sculpt/base/result.h"
#include "sculpt/core/distance/distance_io.h"
#include "sculpt/core/grid/dense_grid.h"
#include "sculpt/core/io/nrrd.h"
#include "sculpt/core/tool/tool.h"
#include "sculpt/core/util/progress.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::core {

/// read_volume_nrrd() or the .vdb density. `window` maps NRRD voxels other
/// than uint8; given for a .vdb it is an error (its density needs none).
Result<Volume> read_volume_file(const std::filesystem::path& path,
                                const VolumeOptions& options = {}, const NrrdLimits& limits = {},
                                const DensityWindow* window = nullptr);
/// write_volume_nrrd() or, for .vdb, level `level` as density and surface.
/// `progress` (optional) follows the .vdb level set, the long part; once it
/// is cancelled nothing is written and the error says "cancelled".
Status write_volume_file(const std::filesystem::path& path, const Volume& volume, int level = 0,
                         Progress* progress = nullptr);

/// A whole volume as density (read_nrrd_density() or the .vdb density).
Result<DenseGrid<uint8_t>> read_density_file(const std::filesystem::path& path,
                                             const DensityWindow* window,
                                             const NrrdLimits& limits = {});
/// The input of the distance commands (read_surface_nrrd()); a .vdb gives
/// its density's level function.
Result<SurfaceVolume> read_surface_file(const std::filesystem::path& path);

/// A uint8 density: NRRD, or .vdb density and surface.
Status write_density_file(const std::filesystem::path& path, const DenseGrid<uint8_t>& density);
/// A signed distance field (voxel units, negative inside): float32 NRRD, or
/// .vdb with the field as the "surface" level set and its density.
Status write_distance_file(const std::filesystem::path& path, const DenseGrid<float>& distance);

/// Tool files: read_tool_nrrd(), or a .vdb density with its sculpt_pivot
/// (the grid's centre without one; checked as the NRRD pivot is).
Result<Tool> read_tool_file(const std::filesystem::path& path, const NrrdLimits& limits = {});
Status write_tool_file(const std::filesystem::path& path, const Tool& tool);

}  // namespace sculpt::core
