#include "sculpt/core/files/volume_file.h"

#include <algorithm>
#include <cmath>

#include <glm/vector_relational.hpp>

#include "sculpt/core/distance/iso_triangulation.h"
#include "sculpt/core/distance/signed_distance.h"
#include "sculpt/core/distance/surface_band.h"
#include "sculpt/core/files/vdb_file.h"
#include "sculpt/core/volume/volume_io.h"

namespace sculpt::core {
namespace {

VdbLimits vdb_limits(const NrrdLimits& limits) {
  VdbLimits out;
  out.max_voxels = std::min(limits.max_voxels, Volume::kMaxVoxels);
  out.max_edge = Volume::kMaxEdge;
  return out;
}

Status refuse_window(const std::filesystem::path& path, const DensityWindow* window) {
  if (window == nullptr) return {};
  return Error(path.string() +
               ": --window and --data-iso map NRRD voxels to density; a .vdb density needs no "
               "mapping");
}

// The density of a .vdb: its "density" grid, or its level set as a distance
// field becomes density.
Result<DenseGrid<uint8_t>> vdb_density(const std::filesystem::path& path,
                                       const NrrdLimits& limits) {
  auto grids = read_vdb(path, vdb_limits(limits));
  if (!grids) return grids.error();
  if (grids->density) return std::move(*grids->density);
  return density_from_distance_field(*grids->surface);
}

bool has_surface(const DenseGrid<float>& distance) {
  bool inside = false;
  bool outside = false;
  for (float v : distance.values()) {
    inside = inside || v < 0.0f;
    outside = outside || v >= 0.0f;
  }
  return inside && outside;
}

Status write_vdb_density(const std::filesystem::path& path, const DenseGrid<uint8_t>& density,
                         std::optional<glm::vec3> pivot, Progress* progress = nullptr) {
  VdbGridsOut grids;
  grids.density = &density;
  grids.pivot = pivot;
  // The level set: the exact distance to the sub-voxel surface (the one the
  // meshes and `sculpt distance` use), so Blender's and Houdini's level-set
  // tools see the surface our meshes have. Only its narrow band is kept, so
  // only the band is measured (the whole-grid transform took 30 s at
  // 256^3). A volume without a surface (empty, solid) has no level set.
  DenseGrid<float> surface;
  const DenseGrid<float> phi = level_function(density);
  if (has_surface(phi)) {
    surface = surface_band_distance(phi, kVdbHalfWidth, 0, progress);
    grids.surface = &surface;
  }
  if (cancelled(progress)) return progress->status().error().in(path.string() + ": not written");
  return write_vdb(path, grids);
}

}  // namespace

Result<Volume> read_volume_file(const std::filesystem::path& path, const VolumeOptions& options,
                                const NrrdLimits& limits, const DensityWindow* window) {
  if (!is_vdb_path(path)) return read_volume_nrrd(path, options, limits, window);
  if (Status st = refuse_window(path, window); !st) return st.error();
  auto density = vdb_density(path, limits);
  if (!density) return density.error();
  if (Status st = Volume::validate(density->dims(), options); !st) {
    return st.error().in(path.string());
  }
  Volume volume = Volume::from_dense(*density, options);
  volume.take_dirty_bricks();  // a freshly loaded volume has nothing to re-mesh "again"
  return volume;
}

Status write_volume_file(const std::filesystem::path& path, const Volume& volume, int level,
                         Progress* progress) {
  if (!is_vdb_path(path)) return write_volume_nrrd(path, volume, level);
  const DenseGrid<uint8_t> density =
      volume.read(Box{glm::ivec3(0), volume.level_dims(level)}, level);
  return write_vdb_density(path, density, std::nullopt, progress);
}

Result<DenseGrid<uint8_t>> read_density_file(const std::filesystem::path& path,
                                             const DensityWindow* window,
                                             const NrrdLimits& limits) {
  if (!is_vdb_path(path)) return read_nrrd_density(path, window, limits);
  if (Status st = refuse_window(path, window); !st) return st.error();
  return vdb_density(path, limits);
}

Result<SurfaceVolume> read_surface_file(const std::filesystem::path& path) {
  if (!is_vdb_path(path)) return read_surface_nrrd(path);
  auto density = vdb_density(path, {});
  if (!density) return density.error();
  SurfaceVolume out;
  out.phi = level_function(*density);
  return out;
}

Status write_density_file(const std::filesystem::path& path, const DenseGrid<uint8_t>& density) {
  if (!is_vdb_path(path)) return write_nrrd(path, density);
  return write_vdb_density(path, density, std::nullopt);
}

Status write_distance_file(const std::filesystem::path& path, const DenseGrid<float>& distance) {
  if (!is_vdb_path(path)) return write_nrrd(path, distance);
  for (size_t i = 0; i < distance.size(); ++i) {
    if (!std::isfinite(distance[i])) {
      const glm::ivec3 d = distance.dims();
      const auto x = static_cast<int>(i % static_cast<size_t>(d.x));
      const auto y = static_cast<int>(i / static_cast<size_t>(d.x) % static_cast<size_t>(d.y));
      const auto z = static_cast<int>(i / (static_cast<size_t>(d.x) * static_cast<size_t>(d.y)));
      return Error(path.string() + ": voxel (" + std::to_string(x) + ", " + std::to_string(y) +
                   ", " + std::to_string(z) + ") is " +
                   (std::isnan(distance[i]) ? "NaN" : "infinite") +
                   ", not a finite number; nothing written");
    }
  }
  const DenseGrid<uint8_t> density = density_from_distance_field(distance);
  VdbGridsOut grids;
  grids.density = &density;
  if (has_surface(distance)) grids.surface = &distance;
  return write_vdb(path, grids);
}

Result<Tool> read_tool_file(const std::filesystem::path& path, const NrrdLimits& limits) {
  if (!is_vdb_path(path)) return read_tool_nrrd(path, limits);
  auto grids = read_vdb(path, vdb_limits(limits));
  if (!grids) return grids.error();
  Tool tool = tool_from_grid(grids->density ? std::move(*grids->density)
                                            : density_from_distance_field(*grids->surface));
  if (grids->pivot) {
    // As read_tool_nrrd(): at most the grid's own size beyond each face.
    const glm::vec3 dims(tool.density.dims());
    const glm::vec3 pivot = *grids->pivot;
    if (glm::any(glm::lessThan(pivot, -dims)) || glm::any(glm::greaterThan(pivot, 2.0f * dims))) {
      return Error(path.string() +
                   ": sculpt_pivot is farther than the grid's size outside the grid");
    }
    tool.pivot = pivot;
  }
  return tool;
}

Status write_tool_file(const std::filesystem::path& path, const Tool& tool) {
  if (!is_vdb_path(path)) return write_tool_nrrd(path, tool);
  return write_vdb_density(path, tool.density, tool.pivot);
}

}  // namespace sculpt::core
