#include "sculpt/station/app/station_controller.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/quaternion.hpp>

#include "make_command.h"
#include "sculpt/core/volume/material_bounds.h"
#include "sculpt/hal/normalizer/normalizer_config.h"
#include "sculpt/sim/synth/session_script.h"
#include "sculpt/station/settings/command_codec.h"

namespace sculpt::station {
namespace {

// A 3D mouse at full deflection turns the camera this fast (rad/s) and moves
// it this many view heights per second.
constexpr float kCameraTurnRate = 2.0f;
constexpr float kCameraMoveRate = 0.8f;
constexpr int64_t kSecondNs = 1'000'000'000;
// One press of a tool-turning key: 15 degrees.
constexpr float kKeyTurnRad = 0.2617994f;
constexpr uint16_t kSpaceMouseVendor = 0x256f;
constexpr uint16_t kSpaceMouseProduct = 0xc635;

}  // namespace

StationController::StationController(ControllerOptions options)
    : options_(std::move(options)), loop_(options_.loop) {
  if (options_.stand_ins) loop_.show_stand_ins(&stand_ins_);
  frame_sculpture();
  device_info_ = sim::scripted_device(kSpaceMouseVendor, kSpaceMouseProduct);
  normalizer_text_ = hal::to_text(hal::NormalizerConfig{});
}

StationController::~StationController() {
  finish_autosave();
  if (recorder_.recording()) (void)recorder_.stop();
}

bool StationController::report(const Status& st, const std::string& done) {
  status_ = st ? done : st.error().message();
  return st.ok();
}

int64_t StationController::stamp(int64_t now_ns) const {
  if (processed_t_ns_ != std::numeric_limits<int64_t>::min()) return processed_t_ns_ + 1;
  return has_device_ ? 0 : now_ns;
}

void StationController::raw_report(const hal::RawEvent& e) {
  recorder_.raw(e);
}

void StationController::command(const sim::Command& c, int64_t now_ns) {
  // The reports held for an offset or closing came before this command.
  let_held_input_go();
  command_at(c, stamp(now_ns));
}

void StationController::command_at(const sim::Command& c, int64_t t_ns) {
  const glm::ivec3 dims = loop_.volume().dims();
  loop_.handle(c);
  // A new block of another size: look at what is in it.
  if (loop_.volume().dims() != dims) frame_sculpture();
  recorder_.command(c, t_ns);
  ++generation_;
}

void StationController::set_tool(sim::ToolShape shape, float a, float b, int64_t now_ns) {
  command(make_command(sim::CommandKind::kTool, choice_of(shape), {a, b}), now_ns);
}
void StationController::set_mode(core::SculptMode mode, int64_t now_ns) {
  command(make_command(sim::CommandKind::kMode, choice_of(mode)), now_ns);
}
void StationController::set_brush(BallBrush brush, int64_t now_ns) {
  command(make_command(sim::CommandKind::kMode, choice_of(brush)), now_ns);
}
void StationController::set_accumulate(bool on, int64_t now_ns) {
  command(make_command(sim::CommandKind::kAccumulate, on ? 1 : 0), now_ns);
}
void StationController::set_strength(float s, int64_t now_ns) {
  command(make_command(sim::CommandKind::kStrength, 0, {std::clamp(s, 0.0f, 1.0f)}), now_ns);
}
void StationController::set_hardness(float h, int64_t now_ns) {
  command(make_command(sim::CommandKind::kHardness, 0, {std::clamp(h, 0.0f, 1.0f)}), now_ns);
}
void StationController::set_spacing(float s, int64_t now_ns) {
  command(make_command(sim::CommandKind::kSpacing, 0, {std::max(s, 0.01f)}), now_ns);
}
void StationController::set_touch(bool on, int64_t now_ns) {
  command(make_command(sim::CommandKind::kTouch, on ? 1 : 0), now_ns);
  status_ = on ? "touch mode: the tool rests on the clay; push past the threshold to sculpt"
               : "touch mode off: the tool passes through the clay";
}

void StationController::set_clutch(bool held, int64_t now_ns) {
  // A key held for seconds is one command, not one a frame.
  if (held == loop_.clutch_key_held()) return;
  command(make_command(sim::CommandKind::kClutch, held ? 1 : 0), now_ns);
}
void StationController::set_tracker_calibration(const hal::TrackerCalibration& t, int64_t now_ns) {
  const glm::dquat& q = t.tracker_to_sculpture;
  command(make_command(sim::CommandKind::kTracker, 0,
                       {static_cast<float>(t.scale_vox_per_mm), static_cast<float>(q.w),
                        static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z)}),
          now_ns);
}

void StationController::set_mirror(std::optional<int> axis, int64_t now_ns) {
  if (!axis) {
    command(make_command(sim::CommandKind::kMirror, sim::kMirrorOff, {0.0f}), now_ns);
    return;
  }
  // The block's middle plane: voxel centres 0..n-1 mirror about (n-1)/2.
  const float at = 0.5f * static_cast<float>(loop_.volume().dims()[*axis] - 1);
  command(make_command(sim::CommandKind::kMirror, static_cast<uint8_t>(*axis), {at}), now_ns);
}
void StationController::undo(int64_t now_ns) {
  const int64_t before = loop_.counters().undos;
  command(make_command(sim::CommandKind::kUndo), now_ns);
  status_ = loop_.counters().undos > before ? "undone" : "nothing to undo";
}
void StationController::redo(int64_t now_ns) {
  const int64_t before = loop_.counters().redos;
  command(make_command(sim::CommandKind::kRedo), now_ns);
  status_ = loop_.counters().redos > before ? "redone" : "nothing to redo";
}

void StationController::frame_sculpture() {
  camera_.frame_material(loop_.volume());
}

bool StationController::use_sculpture_as_tool(int64_t now_ns) {
  const std::optional<core::Box> bounds = core::material_bounds(loop_.volume());
  if (!bounds) {
    status_ = "no material to make a tool of";
    return false;
  }
  return tool_from_box(*bounds, "the sculpture", now_ns);
}

void StationController::hypertexture(int64_t now_ns) {
  constexpr float kSkinWidthVox = 4.0f;
  const glm::vec3 p = loop_.pose().position;
  const uint64_t before = loop_.volume().content_hash();
  command(make_command(sim::CommandKind::kHypertexture, 0,
                       {p.x, p.y, p.z, 0.5f * loop_.tool_size(), kSkinWidthVox,
                        static_cast<float>(++hypertextures_)}),
          now_ns);
  status_ = loop_.volume().content_hash() != before ? "hypertexture baked around the tool"
                                                    : "no surface near the tool for a hypertexture";
}

bool StationController::perform(Action action, int64_t now_ns) {
  const StationSettings& s = loop_.settings();
  auto tool = [&](sim::ToolShape shape) {
    set_tool(shape, s.size_a_vox, s.size_b_vox > 0 ? s.size_b_vox : s.size_a_vox, now_ns);
    return true;
  };
  switch (action) {
    case Action::kUndo:
      undo(now_ns);
      return true;
    case Action::kRedo:
      redo(now_ns);
      return true;
    case Action::kToggleAddSubtract:
      set_mode(
          s.mode == core::SculptMode::kAdd ? core::SculptMode::kSubtract : core::SculptMode::kAdd,
          now_ns);
      return true;
    case Action::kSmooth:
      set_mode(core::SculptMode::kSmooth, now_ns);
      return true;
    case Action::kBrushClay:
      set_brush(BallBrush::kClay, now_ns);
      return true;
    case Action::kBrushFlatten:
      set_brush(BallBrush::kFlatten, now_ns);
      return true;
    case Action::kBrushInflate:
      set_brush(BallBrush::kInflate, now_ns);
      return true;
    case Action::kBrushPinch:
      set_brush(BallBrush::kPinch, now_ns);
      return true;
    case Action::kBrushGrab:
      set_brush(BallBrush::kGrab, now_ns);
      return true;
    case Action::kToggleAccumulate:
      set_accumulate(!s.accumulate, now_ns);
      return true;
    case Action::kToolSphere:
      return tool(sim::ToolShape::kSphere);
    case Action::kToolCube:
      return tool(sim::ToolShape::kCube);
    case Action::kToolCylinder:
      return tool(sim::ToolShape::kCylinder);
    case Action::kToolRing:
      return tool(sim::ToolShape::kRing);
    case Action::kToolCone:
      return tool(sim::ToolShape::kCone);
    case Action::kToolBigger:
    case Action::kToolSmaller: {
      const float f = action == Action::kToolBigger ? 1.25f : 0.8f;
      if (s.custom_tool) return set_tool_scale(s.tool_scale * f, now_ns);
      set_tool(s.shape, std::clamp(s.size_a_vox * f, 1.0f, 64.0f),
               std::clamp(s.size_b_vox * f, 0.0f, 64.0f), now_ns);
      return true;
    }
    case Action::kStronger:
    case Action::kWeaker:
      set_strength(s.strength + (action == Action::kStronger ? 0.1f : -0.1f), now_ns);
      return true;
    case Action::kToggleMirror:
      set_mirror(s.mirror ? std::nullopt : std::optional<int>(0), now_ns);
      return true;
    case Action::kToggleTouch:
      set_touch(!s.touch, now_ns);
      return true;
    case Action::kCentreTool: {
      const glm::vec3 centre = glm::vec3(loop_.volume().dims()) * 0.5f;
      command(make_command(sim::CommandKind::kToolPose, 0,
                           {centre.x, centre.y, centre.z, 1.0f, 0.0f, 0.0f, 0.0f}),
              now_ns);
      status_ = "the tool is at the centre: a tracker's present pose is the centre now";
      return true;
    }
    case Action::kToggleDeviceTarget:
      device_target_ =
          device_target_ == DeviceTarget::kTool ? DeviceTarget::kCamera : DeviceTarget::kTool;
      status_ = device_target_ == DeviceTarget::kTool ? "the 3D mouse moves the tool"
                                                      : "the 3D mouse moves the camera";
      return true;
    case Action::kToggleRecording:
      return recording() ? stop_recording().ok() : start_recording(options_.recording, now_ns).ok();
    case Action::kSave:
      return save(options_.project).ok();
    case Action::kExportMesh:
      return export_mesh(options_.mesh_export).ok();
    case Action::kUseSculptureAsTool:
      return use_sculpture_as_tool(now_ns);
    case Action::kToggleToolRegion:
      if (tool_region_) {
        clear_tool_region();
        status_ = "tool region hidden";
        return true;
      }
      if (!tool_region_from_material()) tool_region_around_tool();
      return true;
    case Action::kUseRegionAsTool:
      return use_region_as_tool(now_ns);
    case Action::kNewBlock:
      return new_block(new_block_, now_ns);
    case Action::kOffsetSculpture:
      return offset_sculpture(offset_vox_, now_ns);
    case Action::kCloseSculpture:
      return close_sculpture(closing_radius_vox_, now_ns);
    case Action::kHypertexture:
      hypertexture(now_ns);
      return true;
    case Action::kFrameView:
      frame_sculpture();
      return true;
    case Action::kTurnToolLeft:
    case Action::kTurnToolRight:
    case Action::kTiltToolUp:
    case Action::kTiltToolDown: {
      const bool turn = action == Action::kTurnToolLeft || action == Action::kTurnToolRight;
      const bool positive = action == Action::kTurnToolLeft || action == Action::kTiltToolUp;
      turn_tool(turn ? camera_.up() : camera_.right(), positive ? kKeyTurnRad : -kKeyTurnRad,
                now_ns);
      return true;
    }
    case Action::kNewSheet:
      new_sheet(now_ns);
      return true;
    case Action::kRemoveSheet:
      remove_sheet(now_ns);
      return loop_.sheet_problem().empty();
    case Action::kToggleSheetEditing:
      set_sheet_editing(!s.sheet_editing, now_ns);
      return true;
    case Action::kSheetAddToMaterial:
    case Action::kSheetSubtractFromMaterial:
      return sheet_into_material(action == Action::kSheetAddToMaterial, now_ns);
    case Action::kSheetAsTool:
      return sheet_as_tool(now_ns);
    case Action::kExportSheet:
      return export_sheet(options_.sheet_export).ok();
  }
  return false;
}

void StationController::set_device(const hal::DeviceInfo& info, const std::string& normalizer) {
  device_info_ = info;
  has_device_ = true;
  normalizer_text_ = normalizer;
  device_.name = info.name;
  device_.backend = info.backend;
}

void StationController::camera_motion(const hal::InputEvent& e) {
  const double dt =
      last_camera_t_ns_ == 0
          ? 0.0
          : std::clamp(static_cast<double>(e.t_ns - last_camera_t_ns_) * 1e-9, 0.0, 0.1);
  last_camera_t_ns_ = e.t_ns;
  const float k = static_cast<float>(dt);
  // Turning the cap turns the object under it: the camera goes the other way.
  camera_.orbit(-e.axes[hal::kRy] * kCameraTurnRate * k, e.axes[hal::kRx] * kCameraTurnRate * k);
  camera_.pan(glm::vec2(-e.axes[hal::kTx], -e.axes[hal::kTy]) * (kCameraMoveRate * k * 1000.0f),
              1000.0f);
  camera_.zoom(std::exp(e.axes[hal::kTz] * kCameraMoveRate * k));
}

int64_t StationController::report_time(const hal::InputEvent& e, int64_t now_ns) {
  // Its reader's clock when it read the report: a played session's reports
  // carry the recording's times, and the millisecond a report can wait for
  // the sculpting thread's poll is latency a user feels.
  if (e.arrived_ns > 0 && e.arrived_ns <= now_ns) return e.arrived_ns;
  // Not from a reader: a hardware report's time if it is this run's, else
  // the poll that took it.
  return e.t_ns <= now_ns && e.t_ns > now_ns - kSecondNs ? e.t_ns : now_ns;
}

void StationController::note_dabs(const StationCounters& before, int64_t t_ns) {
  const StationCounters& now = loop_.counters();
  stats_.note_dabs(now.dabs - before.dabs, t_ns, now.dabs_stood_in - before.dabs_stood_in,
                   loop_.stand_ins_published_ns(), loop_.dabs_not_yet_shown());
}

void StationController::device_frame(
    const hal::InputFrame& frame, int64_t now_ns,
    std::span<const std::pair<int64_t, sim::Command>> device_commands) {
  // In order, every sample: a button acts at the pose of the motion before
  // it, a command between the reports it came between.
  size_t next_command = 0;
  auto commands_until = [&](int64_t t_ns) {
    for (; next_command < device_commands.size() && device_commands[next_command].first <= t_ns;
         ++next_command) {
      command_at(device_commands[next_command].second, device_commands[next_command].first);
    }
  };
  for (const hal::InputEvent& e : frame.events) {
    // Connect events carry the reader's clock, not the device's: only
    // reports place commands.
    const bool report = e.kind == hal::InputKind::kMotion || e.kind == hal::InputKind::kButton ||
                        e.kind == hal::InputKind::kBattery ||
                        e.kind == hal::InputKind::kTrackingLost;
    if (report) {
      commands_until(e.t_ns);
      processed_t_ns_ = std::max(processed_t_ns_, e.t_ns);
    }
    switch (e.kind) {
      case hal::InputKind::kConnected:
        device_.connected = true;
        break;
      case hal::InputKind::kDisconnected:
        device_.connected = false;
        device_.report_rate_hz = 0;
        stats_.restart_report_rate();
        break;
      case hal::InputKind::kBattery:
        device_.battery_percent = e.battery_percent;
        device_.charging = e.charging;
        break;
      case hal::InputKind::kMotion:
        if (device_target_ == DeviceTarget::kCamera) {
          camera_motion(e);
          continue;
        }
        last_camera_t_ns_ = 0;
        break;
      case hal::InputKind::kButton:
      case hal::InputKind::kTrackingLost:
        break;
    }
    const StationCounters before = loop_.counters();
    loop_.handle(e);
    note_dabs(before, report_time(e, now_ns));
  }
  commands_until(std::numeric_limits<int64_t>::max());
  // Every report up to here has been applied: the recording may have them.
  recorder_.release_until(processed_t_ns_);
}

void StationController::reader_samples(int64_t motion_samples, int64_t now_ns) {
  if (const double rate = stats_.reader_samples(motion_samples, now_ns); rate >= 0)
    device_.report_rate_hz = rate;
}

void StationController::pointer_move(glm::vec3 position, int64_t now_ns) {
  const glm::quat q = loop_.pose().orientation;
  const StationCounters before = loop_.counters();
  command(make_command(sim::CommandKind::kPointer, 0,
                       {position.x, position.y, position.z, q.w, q.x, q.y, q.z}),
          now_ns);
  note_dabs(before, now_ns);
}

void StationController::pointer_down(int64_t now_ns) {
  if (pointer_down_) return;
  pointer_down_ = true;
  const StationCounters before = loop_.counters();
  command(make_command(sim::CommandKind::kPress), now_ns);
  note_dabs(before, now_ns);
}

void StationController::pointer_up(int64_t now_ns) {
  if (!pointer_down_) return;
  pointer_down_ = false;
  command(make_command(sim::CommandKind::kRelease), now_ns);
}

int64_t StationController::update_mesh(int64_t now_ns) {
  const int64_t meshed = loop_.update_mesh();
  surface_submitted(++own_change_, now_ns);
  surface_ready(own_change_, own_change_, now_ns);
  return meshed;
}

void StationController::surface_submitted(uint64_t change, int64_t now_ns) {
  // A ball brush's dabs a preview (or the press's end) showed since.
  stats_.still_unshown(loop_.dabs_not_yet_shown());
  // Something to autosave: new dabs, or the sheet moved under the device.
  if (stats_.dabs_waiting() || loop_.sheet().version() != sheet_version_) ++generation_;
  sheet_version_ = loop_.sheet().version();
  stats_.submitted(change, now_ns);
  stand_ins_.handed_over(change);
}

void StationController::surface_ready(uint64_t change, uint64_t full_detail_change,
                                      int64_t ready_ns) {
  stats_.ready(change, full_detail_change, ready_ns);
}

void StationController::tick(int64_t now_ns) {
  if (recorder_.recording()) {
    if (Status st = recorder_.flush(); !st) {
      recording_error_ = st.error().message();
      status_ = "recording stopped: " + recording_error_;
    }
  }
  autosave_if_due(now_ns);
}

}  // namespace sculpt::station
