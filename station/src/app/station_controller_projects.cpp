// StationController: the project file, its autosave, the mesh export and
// the input settings file (the panel's File and Device sections).

#include <chrono>
#include <cstdio>
#include <future>
#include <memory>

#include "sculpt/base/atomic_file.h"
#include "sculpt/base/thread_times.h"
#include "sculpt/core/mesh/marching_cubes.h"
#include "sculpt/core/mesh/mesh_io.h"
#include "sculpt/core/mesh/mesh_simplify.h"
#include "sculpt/hal/normalizer/normalizer_config.h"
#include "sculpt/station/app/station_controller.h"

namespace sculpt::station {

ProjectView StationController::view() const {
  return project_view(camera_, lod_.policy());
}

Status StationController::save(const std::filesystem::path& path) {
  const StationSettings& s = loop_.settings();
  Status st =
      save_project(path, loop_.volume(), s, s.custom_tool ? &loop_.custom_tool_base() : nullptr,
                   view(), loop_.sheet().has_sheet() ? &loop_.sheet().surface() : nullptr);
  if (st) saved_generation_ = generation_;
  report(st, "saved " + path.string());
  return st;
}

Status StationController::open(const std::filesystem::path& path) {
  auto project = load_project(path);
  if (!project) {
    report(project.error(), "");
    return project.error();
  }
  finish_autosave();
  let_held_input_go();
  loop_.restore(std::move(project->volume), project->settings, std::move(project->custom_tool),
                std::move(project->sheet));
  const ProjectView& v = project->view;
  camera_.set(v.camera_target, v.camera_yaw, v.camera_pitch, v.camera_distance);
  lod_.set_policy(v.lod);
  options_.project = path;
  ++generation_;
  saved_generation_ = generation_;
  status_ = "opened " + path.string();
  return {};
}

Status StationController::export_mesh(const std::filesystem::path& path) {
  auto format = core::mesh_format_for(path);
  if (!format) {
    report(format.error(), "");
    return format.error();
  }
  // Full resolution, whatever the view draws.
  core::Mesh mesh = options_.loop.mesh ? (loop_.update_mesh(), loop_.mesh().welded_mesh())
                                       : core::marching_cubes(loop_.volume());
  std::string done = "exported " + path.string();
  if (options_.mesh_export_max_error > 0.0f) {
    const size_t before = mesh.triangles.size();
    core::SimplifiedMesh s = core::simplify_mesh(
        mesh, core::MeshSimplifyOptions{.max_error = options_.mesh_export_max_error});
    mesh = std::move(s.mesh);
    char figures[128];
    std::snprintf(figures, sizeof figures, ": %zu -> %zu triangles, surface moved %.2f voxel",
                  before, mesh.triangles.size(), s.hausdorff);
    done += figures;
  }
  Status st = core::write_mesh(path, mesh, *format);
  report(st, done);
  return st;
}

std::filesystem::path StationController::autosave_path() const {
  std::filesystem::path p = options_.project;
  p += ".autosave";
  return p;
}

void StationController::finish_autosave() {
  if (autosave_.valid()) {
    Status st = autosave_.get();
    if (!st) status_ = "autosave failed: " + st.error().message();
  }
}

void StationController::autosave_if_due(int64_t now_ns) {
  if (options_.autosave_seconds <= 0 || generation_ == saved_generation_) return;
  if (autosave_.valid() && autosave_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
    return;
  if (now_ns - last_autosave_ns_ < static_cast<int64_t>(options_.autosave_seconds * 1e9)) return;
  finish_autosave();
  last_autosave_ns_ = now_ns;
  saved_generation_ = generation_;
  ++autosaves_;
  // A copy of the state is written on another thread, so sculpting goes on
  // while it is compressed and synced.
  auto volume = std::make_shared<core::Volume>(loop_.volume());
  const StationSettings settings = loop_.settings();
  auto tool =
      settings.custom_tool ? std::make_shared<core::Tool>(loop_.custom_tool_base()) : nullptr;
  auto sheet = loop_.sheet().has_sheet()
                   ? std::make_shared<core::nurbs::NurbsSurface>(loop_.sheet().surface())
                   : nullptr;
  autosave_ = std::async(
      std::launch::async, [path = autosave_path(), volume, settings, tool, sheet, view = view()] {
        // Named for traces and --stats: it would carry the sculpting thread's.
        name_this_thread("autosave");
        return save_project(path, *volume, settings, tool.get(), view, sheet.get());
      });
}

Status StationController::save_input_settings(float sensitivity, float deadzone) {
  const std::string& path = options_.normalizer_config_path;
  if (path.empty()) return Error("no input settings file");
  auto config = hal::load_normalizer_config_or_defaults(path);
  if (!config) {
    report(config.error(), "");
    return config.error();
  }
  config->sensitivity.fill(std::clamp(sensitivity, 0.05f, 20.0f));
  config->deadzone.fill(std::clamp(deadzone, 0.0f, 0.9f));
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
  AtomicFileWriter writer(path);
  if (!writer.ok()) return writer.error();
  writer.write(hal::to_text(*config));
  Status st = writer.commit();
  report(st, "saved the input settings to " + path + " (devices opened from now on use them)");
  return st;
}

}  // namespace sculpt::station
