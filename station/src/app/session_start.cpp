#include "sculpt/station/app/session_start.h"

#include <system_error>
#include <utility>

#include "sculpt/station/project/project_file.h"

namespace sculpt::station {

std::filesystem::path session_start_path(const std::filesystem::path& session) {
  std::filesystem::path p = session;
  p += ".start.sculpt";
  return p;
}

Result<bool> restore_session_start(const std::filesystem::path& session, StationLoop& loop) {
  const std::filesystem::path start = session_start_path(session);
  std::error_code ec;
  if (!std::filesystem::exists(start, ec)) return false;
  auto project = load_project(start);
  if (!project) return project.error();
  loop.restore(std::move(project->volume), project->settings, std::move(project->custom_tool),
               std::move(project->sheet));
  return true;
}

}  // namespace sculpt::station
