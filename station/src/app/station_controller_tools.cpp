// The controller's tool making: a region of the sculpture as the tool, any
// custom tool at another size; tool files and meshes as the tool, the tool
// library; a new block; offset and closing.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "make_command.h"
#include "sculpt/core/distance/distance_io.h"
#include "sculpt/core/distance/mesh_distance.h"
#include "sculpt/core/files/mesh_file.h"
#include "sculpt/core/files/volume_file.h"
#include "sculpt/core/tool/tool_scale.h"
#include "sculpt/core/volume/material_bounds.h"
#include "sculpt/sim/session/command_limits.h"
#include "sculpt/station/app/station_controller.h"
#include "sculpt/station/settings/command_codec.h"
#include "sculpt/station/view/tool_outline.h"

namespace sculpt::station {
namespace {

std::string size_text(glm::ivec3 s) {
  return std::to_string(s.x) + "x" + std::to_string(s.y) + "x" + std::to_string(s.z);
}

}  // namespace

void StationController::set_tool_region(const core::Box& box) {
  core::Box clamped;
  const glm::ivec3 dims = loop_.volume().dims();
  clamped.lo = glm::clamp(box.lo, glm::ivec3(0), dims);
  clamped.hi = glm::clamp(box.hi, glm::ivec3(0), dims);
  tool_region_ = clamped;
}

bool StationController::tool_region_from_material() {
  const std::optional<core::Box> bounds = core::material_bounds(loop_.volume());
  if (!bounds) {
    status_ = "no material: the region is not set";
    return false;
  }
  set_tool_region(*bounds);
  status_ = "tool region: the material's bounds, " + size_text(tool_region_->size()) + " voxels";
  return true;
}

void StationController::tool_region_around_tool() {
  const glm::vec3 p = loop_.pose().position;
  const float half = 0.5f * std::max(loop_.tool_size(), 8.0f);
  set_tool_region({glm::ivec3(glm::floor(p - half)), glm::ivec3(glm::ceil(p + half))});
  status_ = "tool region: around the tool, " + size_text(tool_region_->size()) + " voxels";
}

bool StationController::use_region_as_tool(int64_t now_ns) {
  if (!tool_region_) {
    status_ = "no tool region: pick one first";
    return false;
  }
  return tool_from_box(*tool_region_, "the region", now_ns);
}

bool StationController::tool_from_box(core::Box box, const std::string& what, int64_t now_ns) {
  box = core::intersect(box, core::Box{glm::ivec3(0), loop_.volume().dims()});
  if (box.empty()) {
    status_ = what + " is empty: no voxel of the block is in it";
    return false;
  }
  const glm::ivec3 size = box.size();
  if (std::max({size.x, size.y, size.z}) > kMaxToolEdge) {
    status_ = what + " (" + size_text(size) + " voxels) is too big for a tool: at most " +
              std::to_string(kMaxToolEdge) + " voxels a side";
    return false;
  }
  const core::DenseGrid<uint8_t> voxels = loop_.volume().read(box);
  if (std::all_of(voxels.data(), voxels.data() + voxels.size(), [](uint8_t v) { return v == 0; })) {
    status_ = what + " holds no material: no tool made of it";
    return false;
  }
  command(make_command(sim::CommandKind::kToolFromRegion, 0,
                       {static_cast<float>(box.lo.x), static_cast<float>(box.lo.y),
                        static_cast<float>(box.lo.z), static_cast<float>(box.hi.x),
                        static_cast<float>(box.hi.y), static_cast<float>(box.hi.z)}),
          now_ns);
  status_ = what + " is the tool now (" + size_text(size) + " voxels)";
  return true;
}

bool StationController::set_tool_scale(float factor, int64_t now_ns) {
  const StationSettings& s = loop_.settings();
  if (!s.custom_tool) {
    status_ = "a built-in tool changes size by its sizes, not a scale";
    return false;
  }
  factor = std::clamp(factor, sim::kMinToolScale, sim::kMaxToolScale);
  const glm::ivec3 made = loop_.custom_tool_base().density.dims();
  const glm::ivec3 dims = core::scaled_tool_dims(made, factor);
  if (std::max({dims.x, dims.y, dims.z}) > StationLoop::kMaxScaledToolEdge) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "the tool at %.3g times its size would be %s voxels: at most %d a side",
                  double(factor), size_text(dims).c_str(), StationLoop::kMaxScaledToolEdge);
    status_ = text;
    return false;
  }
  command(make_command(sim::CommandKind::kToolScale, 0, {factor}), now_ns);
  char text[120];
  std::snprintf(text, sizeof text, "the tool at %.3g times its size: %s voxels", double(factor),
                size_text(loop_.tool().density.dims()).c_str());
  status_ = text;
  return true;
}

bool StationController::give_tool(const core::Tool& tool, const std::string& what, int64_t now_ns) {
  const glm::ivec3 d = tool.density.dims();
  if (std::max({d.x, d.y, d.z}) > StationLoop::kMaxScaledToolEdge) {
    status_ = what + " (" + size_text(d) + " voxels) is too big for a tool: at most " +
              std::to_string(StationLoop::kMaxScaledToolEdge) + " voxels a side";
    return false;
  }
  sim::Command c{sim::CommandKind::kToolVoxels};
  c.voxels = std::make_shared<const sim::ToolVoxels>(tool_voxels_of(tool));
  command(c, now_ns);
  status_ = what + " is the tool now (" + size_text(d) + " voxels)";
  return true;
}

bool StationController::load_tool(const std::filesystem::path& path, int64_t now_ns) {
  Result<core::Tool> tool = core::read_tool_file(path);
  if (!tool) {
    status_ = tool.error().message();
    return false;
  }
  return give_tool(*tool, path.filename().string(), now_ns);
}

bool StationController::import_mesh_as_tool(const std::filesystem::path& path, int edge,
                                            int64_t now_ns) {
  // As `sculpt voxelize --size edge` (voxelize_command.cpp), with its margin.
  constexpr float kMargin = 2.0f;
  const std::string name = path.string();
  if (edge < 8 || edge > StationLoop::kMaxScaledToolEdge) {
    status_ = name + ": a mesh tool is 8 to " + std::to_string(StationLoop::kMaxScaledToolEdge) +
              " voxels a side, not " + std::to_string(edge);
    return false;
  }
  Result<core::Mesh> mesh = core::read_mesh_file(path);
  if (!mesh) {
    status_ = mesh.error().message();
    return false;
  }
  const core::MeshTopology topo = core::check_topology(*mesh);
  if (!topo.closed()) {
    status_ = name + ": the mesh is not closed (" + std::to_string(topo.boundary_edges) +
              " boundary, " + std::to_string(topo.nonmanifold_edges) + " non-manifold, " +
              std::to_string(topo.misoriented_edges) +
              " mis-oriented edges): inside and outside are undefined";
    return false;
  }
  Result<core::VoxelizeMapping> map = core::fit_mesh_to_grid(*mesh, edge, kMargin);
  if (!map) {
    status_ = map.error().in(name).message();
    return false;
  }
  const core::Mesh placed = core::transform_mesh(*mesh, *map);  // MeshDistance keeps a reference
  const core::MeshDistance distance(placed);
  const core::DenseGrid<float> field = core::mesh_signed_distance(distance, glm::ivec3(edge));
  if (field.at(0, 0, 0) < 0.0f) {
    status_ = name + ": the triangles face inward (wound clockwise seen from outside)";
    return false;
  }
  return give_tool(core::tool_from_grid(core::density_from_distance_field(field)),
                   path.filename().string(), now_ns);
}

Status StationController::save_tool(const std::filesystem::path& path) {
  std::error_code ec;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
  const Status st = core::write_tool_file(path, loop_.tool());
  const glm::ivec3 d = loop_.tool().density.dims();
  report(st, "tool saved to " + path.string() + " (" + size_text(d) + " voxels)");
  return st;
}

StationController::ToolLibrary StationController::scan_tool_library(
    const std::filesystem::path& folder, int thumbnail_px) {
  ToolLibrary library;
  std::error_code ec;
  std::vector<std::filesystem::path> files;
  for (std::filesystem::directory_iterator it(folder, ec), end; !ec && it != end;
       it.increment(ec)) {
    const std::string ext = it->path().extension().string();
    if (ext == ".nrrd" || ext == ".vdb") files.push_back(it->path());
  }
  std::sort(files.begin(), files.end());
  for (const std::filesystem::path& file : files) {
    Result<core::Tool> tool = core::read_tool_file(file);
    if (!tool) {
      ++library.unreadable;
      continue;
    }
    const core::Mesh outline = tool_outline(*tool);
    SoftwareView view = view_of(outline, glm::vec3(0.0f), glm::vec3(tool->density.dims()));
    view.width = view.height = thumbnail_px;
    library.tools.push_back({file, tool->density.dims(), render_mesh(outline, view)});
  }
  return library;
}

bool StationController::new_block(const NewBlockOptions& block, int64_t now_ns) {
  const glm::ivec3 d = block.dims;
  if (glm::any(glm::lessThan(d, glm::ivec3(kMinBlockSide))) ||
      glm::any(glm::greaterThan(d, glm::ivec3(kMaxBlockSide)))) {
    status_ = "a block of " + size_text(d) + " voxels: each side must be " +
              std::to_string(kMinBlockSide) + " to " + std::to_string(kMaxBlockSide) + " voxels";
    return false;
  }
  const glm::vec3 f(d);
  const int margin = std::min({d.x, d.y, d.z}) / 4;
  command(block.fill == BlockFill::kClay
              ? make_command(sim::CommandKind::kVolume, sim::kVolumeClay,
                             {f.x, f.y, f.z, static_cast<float>(margin)})
              : make_command(sim::CommandKind::kVolume, sim::kVolumeFill,
                             {f.x, f.y, f.z, block.fill == BlockFill::kFull ? 255.0f : 0.0f}),
          now_ns);
  // The old region may lie outside the new block.
  tool_region_.reset();
  frame_sculpture();
  status_ = "a new block of " + size_text(d) + " voxels, " +
            (block.fill == BlockFill::kEmpty  ? "empty"
             : block.fill == BlockFill::kFull ? "full"
                                              : "a slab of clay") +
            " (the undo history starts here)";
  return true;
}

bool StationController::offset_sculpture(float by_vox, int64_t now_ns) {
  return morphology(false, by_vox, now_ns);
}

bool StationController::close_sculpture(float radius_vox, int64_t now_ns) {
  return morphology(true, radius_vox, now_ns);
}

bool StationController::morphology(bool close, float by, int64_t now_ns) {
  const char* what = close ? "closing" : "offset";
  const bool in_range = close ? by > 0.0f && by <= sim::kMaxMorphologyVox
                              : std::abs(by) <= sim::kMaxMorphologyVox && by != 0.0f;
  if (!std::isfinite(by) || !in_range) {
    char text[120];
    std::snprintf(text, sizeof text, "no %s by %g voxels: it takes %s", what, double(by),
                  close ? "a radius above 0, at most 64 voxels" : "-64 to 64 voxels, not 0");
    status_ = text;
    return false;
  }
  command(make_command(sim::CommandKind::kMorphology,
                       close ? sim::kMorphologyClose : sim::kMorphologyOffset, {by}),
          now_ns);
  if (loop_.morphology_pending()) {
    // Computing in the background: the status says so until it lands.
    char text[120];
    std::snprintf(text, sizeof text, "%s by %+g voxels...", close ? "closing" : "offsetting",
                  double(by));
    status_ = text;
    landing_ = Landing{close, by};
    return true;
  }
  return morphology_status(close, by);
}

bool StationController::morphology_status(bool close, float by) {
  const MorphologyResult& r = loop_.last_morphology();
  if (!r.applied) {
    status_ = std::string("no surface to ") + (close ? "close" : "offset") +
              ": the block is empty or solid";
    return false;
  }
  char text[160];
  std::snprintf(text, sizeof text, "%s by %+g voxels: %lld -> %lld voxels inside (one undo step)",
                close ? "closed" : "offset", double(by), static_cast<long long>(r.inside_before),
                static_cast<long long>(r.inside_after));
  status_ = text;
  return true;
}

void StationController::let_held_input_go() {
  if (loop_.morphology_pending() && input_barrier_) input_barrier_();
}

bool StationController::land_morphology(bool wait) {
  if (loop_.morphology_pending() && (wait || loop_.morphology_ready())) loop_.settle();
  if (loop_.morphology_pending()) return false;
  // Landed now, or by an input that settled it: the status tells how.
  if (landing_) {
    morphology_status(landing_->close, landing_->by);
    landing_.reset();
    ++generation_;  // something to autosave
  }
  return true;
}

}  // namespace sculpt::station
