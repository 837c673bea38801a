#pragma once
// Project files (".sculpt"): the whole state of a station in one file, so a
// sculpture can be closed and opened again exactly as it was.
//
// Layout (integers little endian):
//   8 bytes  "SCULPTPJ"
//   u32      version (1)
//   u32      n, then n bytes of JSON: {"volume": {"dims", "brick_edge", "levels",
//            "content_hash"}, "settings": {...}, "view": {...}, "tool": null |
//            {"dims", "pivot"}, "sheet": null | a NURBS surface (nurbs_json.h)}
//            (docs/formats.md lists every field)
//   u64      m, then m bytes of zlib (deflate) data holding, for every brick in
//            index order, u8 0 + u8 value (a uniform brick) or u8 1 + the
//            brick's edge^3 int16 Haar coefficients (wavelet_pyramid.h layout);
//            then the custom tool's density, dims.x * dims.y * dims.z bytes
//   u32      CRC-32 of everything before it
// The volume is stored as its wavelet bricks, as the station holds it: the
// detail coefficients of a sculpture are mostly zero, which deflate packs
// well. Opening checks the CRC, every size against the file, and the content
// hash of the rebuilt volume, so a damaged file is refused, never half-read.

#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include <glm/vec3.hpp>

#include "sculpt/base/result.h"
#include "sculpt/core/nurbs/nurbs_surface.h"
#include "sculpt/core/tool/tool.h"
#include "sculpt/core/volume/volume.h"
#include "sculpt/station/settings/station_settings.h"
#include "sculpt/station/view/lod_selector.h"
#include "sculpt/station/view/orbit_camera.h"

namespace sculpt::station {

/// How the project was being looked at.
struct ProjectView {
  glm::vec3 camera_target{128.0f};
  float camera_yaw = 0.5f;
  float camera_pitch = 0.35f;
  float camera_distance = 600.0f;
  LodPolicy lod;
};

/// The view through `camera` at level-of-detail policy `lod`.
ProjectView project_view(const OrbitCamera& camera, const LodPolicy& lod = {});

struct Project {
  std::unique_ptr<core::Volume> volume;
  StationSettings settings;
  /// The tool when settings.custom_tool (a sculpture made a tool), as made:
  /// settings.tool_scale scales it (StationLoop::restore).
  std::optional<core::Tool> custom_tool;
  ProjectView view;
  /// The NURBS sheet, if there was one.
  std::optional<core::nurbs::NurbsSurface> sheet;
};

inline constexpr uint32_t kProjectVersion = 1;

/// Writes the project atomically (temporary file, fsync, rename).
Status save_project(const std::filesystem::path& path, const core::Volume& volume,
                    const StationSettings& settings, const core::Tool* custom_tool,
                    const ProjectView& view, const core::nurbs::NurbsSurface* sheet = nullptr);

/// Opens a project; errors name the file and what is wrong with it.
Result<Project> load_project(const std::filesystem::path& path);
/// A project from its bytes; errors start with `name` (load_project() and
/// the fuzz target read through this).
Result<Project> parse_project(std::span<const uint8_t> bytes, const std::string& name);

}  // namespace sculpt::station
