#pragma once
// Reading the inputs of the distance commands: a uint8 density volume
// (inside: density above 127.5) or a float32 field (inside: negative, e.g. a
// distance field written by `sculpt distance`).

#include <filesystem>

#include "sculpt/base/result.h"
#include "sculpt/core/grid/dense_grid.h"

namespace sculpt::core {

struct SurfaceVolume {
  /// Level function, negative inside (level_function() of a density).
  DenseGrid<float> phi;
  /// Whether the file held uint8 density (else float32).
  bool from_density = true;
};

/// Reads a uint8 or float32 NRRD; errors name the file.
Result<SurfaceVolume> read_surface_nrrd(const std::filesystem::path& path);

/// A distance field needs a surface: an error naming `path` when the volume
/// is empty or solid throughout (its distance would be infinite everywhere).
Status require_surface(const SurfaceVolume& volume, const std::filesystem::path& path);

/// uint8 density of a signed distance field (analytic_shapes.h ramp).
DenseGrid<uint8_t> density_from_distance_field(const DenseGrid<float>& distance);

}  // namespace sculpt::core
