#pragma once
// NRRD in and out of the bricked volume, streamed a slab of bricks at a time:
// a 1024^3 file is encoded without ever holding it densely.

#include <filesystem>

#include "sculpt/core/io/nrrd.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::core {

/// Reads a NRRD into a volume: uint8 voxels as they are, any type through
/// `window` (nrrd.h: DensityWindow).
Result<Volume> read_volume_nrrd(const std::filesystem::path& path,
                                const VolumeOptions& options = {}, const NrrdLimits& limits = {},
                                const DensityWindow* window = nullptr);
/// Writes level `level` of the volume (ceil(dims / 2^level) voxels) as uint8 NRRD.
Status write_volume_nrrd(const std::filesystem::path& path, const Volume& volume, int level = 0);

}  // namespace sculpt::core
