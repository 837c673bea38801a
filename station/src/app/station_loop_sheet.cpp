// The StationLoop's NURBS sheet commands (sim::SheetAction): placing and
// removing the sheet, sheet editing, and the sheet's shell into the material
// or as the tool. Values out of range are clamped, non-finite ones ignored,
// so any recorded command replays without harm.

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

#include "sculpt/core/nurbs/sheet_voxelizer.h"
#include "sculpt/core/nurbs/surface_tessellator.h"
#include "sculpt/station/app/station_loop.h"

namespace sculpt::station {
namespace {

// A tool is rotated per dab: beyond this size a sheet makes too slow a tool.
constexpr int kMaxSheetToolVox = 160;

bool finite(const float* v, int n) {
  return std::all_of(v, v + n, [](float x) { return std::isfinite(x); });
}

// The voxel box within `reach` of the mesh's vertices (half-open).
core::Box mesh_box(const core::Mesh& mesh, float reach) {
  const auto [lo, hi] = core::mesh_bounds(mesh);
  return core::Box{glm::ivec3(glm::floor(lo - reach)), glm::ivec3(glm::ceil(hi + reach)) + 1};
}

// The sheet finely tessellated for voxelising: about two cells per voxel of
// its extent (the drawn mesh's 64 cells leave facets a steep pull shows as
// terraces in the material).
core::Mesh fine_mesh(const core::nurbs::NurbsSurface& surface, const core::Mesh& drawn) {
  const core::Box box = mesh_box(drawn, 0.0f);
  const glm::ivec3 d = box.size();
  const int cells = std::clamp(2 * std::max({d.x, d.y, d.z}), 64, 384);
  return core::nurbs::SurfaceTessellator::with_cells(surface, cells, cells).mesh();
}

}  // namespace

void StationLoop::sheet_command(const sim::Command& c) {
  using A = sim::SheetAction;
  sheet_problem_.clear();
  if (pressed_) release();
  switch (static_cast<A>(c.choice)) {
    case A::kPlace: {
      if (!finite(c.values, 6)) return;
      const double size = std::clamp(c.values[3], 4.0f, 4096.0f);
      const int points = std::clamp(static_cast<int>(c.values[4]), 4, 64);
      const int axis = std::clamp(static_cast<int>(c.values[5]), 0, 2);
      sheet_.set(
          SheetEditor::flat(glm::dvec3(c.values[0], c.values[1], c.values[2]), size, points, axis));
      return;
    }
    case A::kRemove:
      if (sheet_.has_sheet()) sheet_.set(std::nullopt);
      return;
    case A::kEdit:
      settings_.sheet_editing = c.values[0] != 0.0f;
      settings_.sheet_drag.influence =
          static_cast<SheetInfluence>(std::clamp(static_cast<int>(c.values[1]), 0, 2));
      if (std::isfinite(c.values[2])) {
        settings_.sheet_drag.radius = std::clamp(static_cast<double>(c.values[2]), 0.0, 64.0);
      }
      return;
    case A::kAdd:
    case A::kSubtract:
    case A::kTool: {
      if (!sheet_.has_sheet()) {
        sheet_problem_ = "there is no sheet";
        return;
      }
      const float thickness =
          std::isfinite(c.values[0]) ? std::clamp(c.values[0], 0.5f, 64.0f) : 2.0f;
      if (static_cast<A>(c.choice) == A::kTool) {
        sheet_as_tool(thickness);
      } else {
        sheet_into_material(thickness, static_cast<A>(c.choice) == A::kAdd);
      }
      return;
    }
  }
}

void StationLoop::sheet_into_material(float thickness, bool add) {
  const core::Mesh mesh = fine_mesh(sheet_.surface(), sheet_.mesh());
  const core::Box box = core::intersect(mesh_box(mesh, 0.5f * thickness + 1.0f),
                                        core::Box{glm::ivec3(0), volume_->dims()});
  if (box.empty()) {
    sheet_problem_ = "the sheet is outside the block";
    return;
  }
  const auto mode = add ? core::nurbs::ShellMode::kAdd : core::nurbs::ShellMode::kSubtract;
  sculptor_->external_edit(box,
                           [&] { core::nurbs::voxelize_shell(mesh, thickness, mode, *volume_); });
  // Undo should now reach this edit of the material, not the sheet.
  settings_.sheet_editing = false;
}

void StationLoop::sheet_as_tool(float thickness) {
  const core::Mesh mesh = fine_mesh(sheet_.surface(), sheet_.mesh());
  const core::Box box = mesh_box(mesh, 0.5f * thickness + 1.0f);
  const glm::ivec3 dims = box.size();
  if (std::max({dims.x, dims.y, dims.z}) > kMaxSheetToolVox) {
    sheet_problem_ = "the sheet is too big for a tool (" +
                     std::to_string(std::max({dims.x, dims.y, dims.z})) + " voxels; at most " +
                     std::to_string(kMaxSheetToolVox) + ")";
    return;
  }
  core::Mesh local = mesh;
  for (glm::vec3& p : local.positions)
    p -= glm::vec3(box.lo);
  core::Volume shell(dims, 0);
  core::nurbs::voxelize_shell(local, thickness, core::nurbs::ShellMode::kAdd, shell);
  set_custom_tool(core::tool_from_volume(shell, core::Box{glm::ivec3(0), dims}),
                  CustomToolSource::kSheet);
  settings_.sheet_editing = false;  // the new tool is for sculpting
}

}  // namespace sculpt::station
