#include "sculpt/core/distance/distance_io.h"

#include <algorithm>
#include <cmath>

#include "sculpt/core/distance/iso_triangulation.h"
#include "sculpt/core/io/nrrd.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core {

Result<SurfaceVolume> read_surface_nrrd(const std::filesystem::path& path) {
  auto reader = NrrdReader::open(path);
  if (!reader) return reader.error();
  const NrrdType type = reader->header().type;
  SurfaceVolume out;
  if (type == NrrdType::kUInt8) {
    auto grid = read_nrrd_u8(path);
    if (!grid) return grid.error();
    out.phi = level_function(*grid);
  } else {
    auto grid = read_nrrd_f32(path);
    if (!grid) return grid.error();
    for (float v : grid->values())
      if (std::isnan(v)) return Error(path.string() + ": float volume holds NaN");
    out.phi = std::move(*grid);
    out.from_density = false;
  }
  return out;
}

Status require_surface(const SurfaceVolume& volume, const std::filesystem::path& path) {
  const auto& phi = volume.phi.values();
  const bool inside = std::any_of(phi.begin(), phi.end(), [](float v) { return v < 0.0f; });
  const bool outside = std::any_of(phi.begin(), phi.end(), [](float v) { return v >= 0.0f; });
  if (inside && outside) return {};
  return Error(path.string() + ": " + (inside ? "solid throughout" : "holds no material") +
               ", so it has no surface to measure a distance from");
}

DenseGrid<uint8_t> density_from_distance_field(const DenseGrid<float>& distance) {
  DenseGrid<uint8_t> out(distance.dims());
  for (size_t i = 0; i < distance.size(); ++i)
    out[i] = density_from_distance(distance[i]);
  return out;
}

}  // namespace sculpt::core
