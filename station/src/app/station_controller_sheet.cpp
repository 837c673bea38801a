// The controller's NURBS sheet actions and the keyboard's tool turning: each
// becomes a station command, so recordings carry them.

#include <cmath>

#include <glm/common.hpp>
#include <glm/gtc/quaternion.hpp>

#include "make_command.h"
#include "sculpt/core/mesh/mesh_io.h"
#include "sculpt/core/nurbs/nurbs_json.h"
#include "sculpt/core/nurbs/nurbs_obj.h"
#include "sculpt/station/app/station_controller.h"

namespace sculpt::station {
namespace {

constexpr int kNewSheetPoints = 8;

sim::Command sheet_command(sim::SheetAction action, std::initializer_list<float> values = {}) {
  return make_command(sim::CommandKind::kSheet, static_cast<uint8_t>(action), values);
}

}  // namespace

void StationController::turn_tool(glm::vec3 axis, float angle, int64_t now_ns) {
  const hal::ToolPose& pose = loop_.pose();
  const glm::quat q =
      glm::normalize(glm::angleAxis(angle, glm::normalize(axis)) * pose.orientation);
  const glm::vec3 p = pose.position;
  command(make_command(sim::CommandKind::kPointer, 0, {p.x, p.y, p.z, q.w, q.x, q.y, q.z}), now_ns);
}

void StationController::new_sheet(int64_t now_ns) {
  // Facing the camera: normal to the axis the view looks most along.
  const glm::vec3 f = glm::abs(camera_.forward());
  const int axis = f.x >= f.y && f.x >= f.z ? 0 : (f.y >= f.z ? 1 : 2);
  const glm::vec3 dims(loop_.volume().dims());
  const float size = 0.5f * std::min(dims[(axis + 1) % 3], dims[(axis + 2) % 3]);
  // Through the tool along the normal, centred in the block across it.
  glm::vec3 centre = 0.5f * (dims - 1.0f);
  centre[axis] = std::clamp(loop_.pose().position[axis], 0.0f, dims[axis] - 1.0f);
  command(sheet_command(sim::SheetAction::kPlace,
                        {centre.x, centre.y, centre.z, size, static_cast<float>(kNewSheetPoints),
                         static_cast<float>(axis)}),
          now_ns);
  set_sheet_editing(true, now_ns);
  status_ = "a new sheet through the tool: press and move to drag it";
}

void StationController::remove_sheet(int64_t now_ns) {
  if (!loop_.sheet().has_sheet()) {
    status_ = "there is no sheet";
    return;
  }
  command(sheet_command(sim::SheetAction::kRemove), now_ns);
  status_ = "sheet removed (Undo in sheet editing brings it back)";
}

void StationController::set_sheet_editing(bool on, int64_t now_ns) {
  const StationSettings& s = loop_.settings();
  command(sheet_command(sim::SheetAction::kEdit,
                        {on ? 1.0f : 0.0f, static_cast<float>(s.sheet_drag.influence),
                         static_cast<float>(s.sheet_drag.radius)}),
          now_ns);
  status_ = on ? "sheet editing: presses grab the sheet, Undo acts on it"
               : "sculpting: presses shape the material";
}

void StationController::set_sheet_influence(SheetInfluence influence, float radius,
                                            int64_t now_ns) {
  command(sheet_command(sim::SheetAction::kEdit, {loop_.settings().sheet_editing ? 1.0f : 0.0f,
                                                  static_cast<float>(influence), radius}),
          now_ns);
}

bool StationController::sheet_into_material(bool add, int64_t now_ns) {
  const uint64_t before = loop_.volume().content_hash();
  command(
      sheet_command(add ? sim::SheetAction::kAdd : sim::SheetAction::kSubtract, {sheet_thickness_}),
      now_ns);
  if (!loop_.sheet_problem().empty()) {
    status_ = loop_.sheet_problem();
    return false;
  }
  status_ = loop_.volume().content_hash() == before
                ? "the sheet's shell changed nothing"
                : std::string(add ? "the sheet's shell added to" : "the sheet's shell cut from") +
                      " the material (sculpting again; Undo takes it back)";
  return true;
}

bool StationController::sheet_as_tool(int64_t now_ns) {
  command(sheet_command(sim::SheetAction::kTool, {sheet_thickness_}), now_ns);
  status_ =
      loop_.sheet_problem().empty() ? "the sheet's shell is the tool now" : loop_.sheet_problem();
  return loop_.sheet_problem().empty();
}

Status StationController::export_sheet(const std::filesystem::path& stem) {
  if (!loop_.sheet().has_sheet()) {
    status_ = "there is no sheet to export";
    return Error(status_);
  }
  auto with = [&](const char* ext) {
    std::filesystem::path p = stem;
    p += ext;
    return p;
  };
  const core::nurbs::NurbsSurface& s = loop_.sheet().surface();
  Status st = core::nurbs::write_json(with(".json"), s);
  if (st) st = core::nurbs::write_freeform_obj(with(".obj"), s);
  if (st) st = core::write_mesh(with(".ply"), loop_.sheet().mesh(), core::MeshFormat::kPlyBinary);
  report(st, "sheet exported: " + with(".json").string() + " (NURBS), " + with(".obj").string() +
                 " (free-form), " + with(".ply").string() + " (mesh)");
  return st;
}

}  // namespace sculpt::station
