// StationController: recording a session of what the user does, from the
// settings (and, unless the station is as it started, the sculpture) at
// its start.

#include <chrono>

#include "make_command.h"
#include "sculpt/station/app/session_start.h"
#include "sculpt/station/app/station_controller.h"
#include "sculpt/station/settings/command_codec.h"

namespace sculpt::station {

std::vector<sim::Command> StationController::opening_commands(bool with_block) const {
  const StationSettings& s = loop_.settings();
  const hal::ToolPose& p = loop_.pose();
  std::vector<sim::Command> c;
  const glm::vec3 d(loop_.volume().dims());
  const StationLoop::Options& o = options_.loop;
  // The block the station started with, unless the recording starts from a
  // saved project (start_recording).
  if (with_block) {
    c.push_back(o.clay_margin > 0
                    ? make_command(sim::CommandKind::kVolume, sim::kVolumeClay,
                                   {d.x, d.y, d.z, static_cast<float>(o.clay_margin)})
                    : make_command(sim::CommandKind::kVolume, sim::kVolumeFill,
                                   {d.x, d.y, d.z, static_cast<float>(o.volume_fill)}));
  }
  // A custom tool comes with the sculpture saved beside the session (it
  // exists whenever one is the tool: making one is a command); a tool
  // command here would put the built-in shape back.
  if (!s.custom_tool) {
    c.push_back(
        make_command(sim::CommandKind::kTool, choice_of(s.shape), {s.size_a_vox, s.size_b_vox}));
  }
  c.push_back(make_command(sim::CommandKind::kMode, choice_of(s.mode)));
  // The brush after the mode: a replay keeps both, as the station had them.
  if (s.brush) c.push_back(make_command(sim::CommandKind::kMode, choice_of(*s.brush)));
  c.push_back(make_command(sim::CommandKind::kStrength, 0, {s.strength}));
  c.push_back(make_command(sim::CommandKind::kHardness, 0, {s.hardness}));
  c.push_back(make_command(sim::CommandKind::kSpacing, 0, {s.spacing}));
  c.push_back(make_command(sim::CommandKind::kAccumulate, s.accumulate ? 1 : 0));
  c.push_back(s.mirror ? make_command(sim::CommandKind::kMirror,
                                      static_cast<uint8_t>(s.mirror->axis), {s.mirror->centre_vox})
                       : make_command(sim::CommandKind::kMirror, sim::kMirrorOff, {0.0f}));
  const SheetDragOptions& drag = s.sheet_drag;
  c.push_back(make_command(sim::CommandKind::kSheet, static_cast<uint8_t>(sim::SheetAction::kEdit),
                           {s.sheet_editing ? 1.0f : 0.0f, static_cast<float>(drag.influence),
                            static_cast<float>(drag.radius)}));
  c.push_back(make_command(sim::CommandKind::kTouch, s.touch ? 1 : 0));
  // A recording started with the clutch key held replays clutched too, and
  // re-anchors when the key is let go, as the live station does.
  c.push_back(make_command(sim::CommandKind::kClutch, loop_.clutch_key_held() ? 1 : 0));
  const glm::dquat& q = s.tracker.tracker_to_sculpture;
  c.push_back(
      make_command(sim::CommandKind::kTracker, 0,
                   {static_cast<float>(s.tracker.scale_vox_per_mm), static_cast<float>(q.w),
                    static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z)}));
  c.push_back(make_command(sim::CommandKind::kToolPose, 0,
                           {p.position.x, p.position.y, p.position.z, p.orientation.w,
                            p.orientation.x, p.orientation.y, p.orientation.z}));
  return c;
}

Status StationController::start_recording(const std::filesystem::path& path, int64_t now_ns) {
  sim::SessionHeader header;
  header.device = device_info_;
  header.normalizer_config = normalizer_text_;
  header.created_unix_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                               std::chrono::system_clock::now().time_since_epoch())
                               .count();
  // The opening commands rebuild the settings. Unless the station is as it
  // started, the sculpture (and sheet and tool) is saved beside the session
  // and replays restore it; a fresh start removes a stale one of that name.
  const bool fresh = generation_ == 0;
  const std::filesystem::path start = session_start_path(path);
  std::error_code ec;
  if (fresh) {
    std::filesystem::remove(start, ec);
  } else {
    const StationSettings& s = loop_.settings();
    Status saved =
        save_project(start, loop_.volume(), s, s.custom_tool ? &loop_.custom_tool_base() : nullptr,
                     view(), loop_.sheet().has_sheet() ? &loop_.sheet().surface() : nullptr);
    if (!saved) {
      report(saved, "");
      return saved;
    }
  }
  // Reports the readers tapped but the station has not applied yet wait for
  // it: before the first poll a device's commands (a session playing as a
  // device) are not applied either, and a command applied later at an
  // earlier time must still come before them in the file.
  recorder_.release_until(processed_t_ns_);
  Status st = recorder_.start(path, header, opening_commands(/*with_block=*/fresh), stamp(now_ns));
  report(st, "recording to " + path.string() +
                 (fresh ? "" : " (starting from this sculpture, saved as " + start.string() + ")"));
  return st;
}

Status StationController::stop_recording() {
  auto records = recorder_.stop();
  if (!records) {
    report(records.error(), "");
    return records.error();
  }
  status_ = "recorded " + std::to_string(*records) + " records to " + recorder_.path().string();
  return {};
}

}  // namespace sculpt::station
