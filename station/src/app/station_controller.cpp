#include "sculpt/station/app/station_controller.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

#include <glm/gtc/quaternion.hpp>

#include "make_command.h"
#include "sculpt/base/atomic_file.h"
#include "sculpt/core/mesh/marching_cubes.h"
#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/mesh/mesh_io.h"
#include "sculpt/core/volume/material_bounds.h"
#include "sculpt/hal/normalizer/normalizer_config.h"
#include "sculpt/sim/synth/session_script.h"
#include "sculpt/station/app/session_start.h"
#include "sculpt/station/settings/command_codec.h"

namespace sculpt::station {
namespace {

constexpr size_t kRecentDabs = 256;
// The largest sculpture that becomes a tool: a tool is rotated voxel by voxel
// at every new orientation, so it must stay small next to the block.
constexpr int kMaxToolEdge = 96;
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
void StationController::set_strength(float s, int64_t now_ns) {
  command(make_command(sim::CommandKind::kStrength, 0, {std::clamp(s, 0.0f, 1.0f)}), now_ns);
}
void StationController::set_spacing(float s, int64_t now_ns) {
  command(make_command(sim::CommandKind::kSpacing, 0, {std::max(s, 0.01f)}), now_ns);
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
  // The material, not the block around it (a clay slab or a head fills a
  // fifth of a 256^3 block's view); an empty block is framed whole.
  const std::optional<core::Box> bounds = core::material_bounds(loop_.volume());
  if (bounds) {
    camera_.frame(glm::vec3(bounds->lo), glm::vec3(bounds->hi));
  } else {
    camera_.frame(glm::vec3(0.0f), glm::vec3(loop_.volume().dims()));
  }
}

bool StationController::use_sculpture_as_tool(int64_t now_ns) {
  const std::optional<core::Box> bounds = core::material_bounds(loop_.volume());
  if (!bounds) {
    status_ = "no material to make a tool of";
    return false;
  }
  const core::Box tight = *bounds;
  const glm::ivec3 size = tight.size();
  if (std::max({size.x, size.y, size.z}) > kMaxToolEdge) {
    status_ = "the sculpture (" + std::to_string(size.x) + "x" + std::to_string(size.y) + "x" +
              std::to_string(size.z) + " voxels) is too big for a tool: at most " +
              std::to_string(kMaxToolEdge) + " voxels a side";
    return false;
  }
  command(make_command(sim::CommandKind::kToolFromRegion, 0,
                       {static_cast<float>(tight.lo.x), static_cast<float>(tight.lo.y),
                        static_cast<float>(tight.lo.z), static_cast<float>(tight.hi.x),
                        static_cast<float>(tight.hi.y), static_cast<float>(tight.hi.z)}),
          now_ns);
  status_ = "the sculpture is the tool now";
  return true;
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
      if (s.custom_tool) {
        status_ = "a sculpture tool keeps its size";
        return false;
      }
      const float f = action == Action::kToolBigger ? 1.25f : 0.8f;
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

int64_t StationController::report_time(int64_t t_ns, int64_t now_ns) {
  // A hardware report carries the monotonic time it was read at; a sim
  // device's carries the time recorded in its session, which says nothing
  // about this run: its latency counts from the frame that received it.
  return t_ns <= now_ns && t_ns > now_ns - kSecondNs ? t_ns : now_ns;
}

void StationController::note_dabs(int64_t dabs_before, int64_t t_ns) {
  unmeshed_dab_t_ns_.insert(unmeshed_dab_t_ns_.end(),
                            static_cast<size_t>(loop_.counters().dabs - dabs_before), t_ns);
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
                        e.kind == hal::InputKind::kBattery;
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
        rate_since_ns_ = 0;
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
        break;
    }
    const int64_t dabs = loop_.counters().dabs;
    loop_.handle(e);
    note_dabs(dabs, report_time(e.t_ns, now_ns));
  }
  commands_until(std::numeric_limits<int64_t>::max());
  // Every report up to here has been applied: the recording may have them.
  recorder_.release_until(processed_t_ns_);
}

void StationController::reader_samples(int64_t motion_samples, int64_t now_ns) {
  // Motion samples the reader decoded (dropped ones included: the device
  // sent them), averaged over about a second.
  if (rate_since_ns_ == 0 || motion_samples < rate_samples_) {
    rate_since_ns_ = now_ns;
    rate_samples_ = motion_samples;
    return;
  }
  const int64_t dt = now_ns - rate_since_ns_;
  if (dt < kSecondNs) return;
  device_.report_rate_hz =
      static_cast<double>(motion_samples - rate_samples_) * 1e9 / static_cast<double>(dt);
  rate_since_ns_ = now_ns;
  rate_samples_ = motion_samples;
}

void StationController::pointer_move(glm::vec3 position, int64_t now_ns) {
  const glm::quat q = loop_.pose().orientation;
  const int64_t dabs = loop_.counters().dabs;
  command(make_command(sim::CommandKind::kPointer, 0,
                       {position.x, position.y, position.z, q.w, q.x, q.y, q.z}),
          now_ns);
  note_dabs(dabs, now_ns);
}

void StationController::pointer_down(int64_t now_ns) {
  if (pointer_down_) return;
  pointer_down_ = true;
  const int64_t dabs = loop_.counters().dabs;
  command(make_command(sim::CommandKind::kPress), now_ns);
  note_dabs(dabs, now_ns);
}

void StationController::pointer_up(int64_t now_ns) {
  if (!pointer_down_) return;
  pointer_down_ = false;
  command(make_command(sim::CommandKind::kRelease), now_ns);
}

int64_t StationController::update_mesh(int64_t now_ns) {
  const int64_t meshed = loop_.update_mesh();
  surface_submitted(++own_change_);
  surface_ready(own_change_, now_ns);
  return meshed;
}

void StationController::surface_submitted(uint64_t change) {
  // Something to autosave: new dabs, or the sheet moved under the device.
  if (!unmeshed_dab_t_ns_.empty() || loop_.sheet().version() != sheet_version_) ++generation_;
  sheet_version_ = loop_.sheet().version();
  for (int64_t t : unmeshed_dab_t_ns_)
    meshing_dabs_.push_back({change, t});
  unmeshed_dab_t_ns_.clear();
}

void StationController::surface_ready(uint64_t change, int64_t ready_ns) {
  while (!meshing_dabs_.empty() && meshing_dabs_.front().change <= change) {
    const double us = static_cast<double>(ready_ns - meshing_dabs_.front().report_t_ns) * 1e-3;
    meshing_dabs_.pop_front();
    recent_latency_us_.push_back(us);
    if (recent_latency_us_.size() > kRecentDabs) recent_latency_us_.pop_front();
    all_latency_us_.add(us);
  }
}

LatencyStats StationController::recent_latency() const {
  return latency_stats({recent_latency_us_.begin(), recent_latency_us_.end()});
}
LatencyStats StationController::session_latency() const {
  return latency_stats(all_latency_us_);
}

ProjectView StationController::view() const {
  ProjectView v;
  v.camera_target = camera_.target();
  v.camera_yaw = camera_.yaw();
  v.camera_pitch = camera_.pitch();
  v.camera_distance = camera_.distance();
  v.lod = lod_.policy();
  return v;
}

Status StationController::save(const std::filesystem::path& path) {
  const StationSettings& s = loop_.settings();
  Status st = save_project(path, loop_.volume(), s, s.custom_tool ? &loop_.tool() : nullptr, view(),
                           loop_.sheet().has_sheet() ? &loop_.sheet().surface() : nullptr);
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
  const core::Mesh mesh = options_.loop.mesh ? (loop_.update_mesh(), loop_.mesh().welded_mesh())
                                             : core::marching_cubes(loop_.volume());
  Status st = core::write_mesh(path, mesh, *format);
  report(st, "exported " + path.string());
  return st;
}

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
  c.push_back(
      make_command(sim::CommandKind::kTool, choice_of(s.shape), {s.size_a_vox, s.size_b_vox}));
  c.push_back(make_command(sim::CommandKind::kMode, choice_of(s.mode)));
  c.push_back(make_command(sim::CommandKind::kStrength, 0, {s.strength}));
  c.push_back(make_command(sim::CommandKind::kSpacing, 0, {s.spacing}));
  c.push_back(s.mirror ? make_command(sim::CommandKind::kMirror,
                                      static_cast<uint8_t>(s.mirror->axis), {s.mirror->centre_vox})
                       : make_command(sim::CommandKind::kMirror, sim::kMirrorOff, {0.0f}));
  const SheetDragOptions& drag = s.sheet_drag;
  c.push_back(make_command(sim::CommandKind::kSheet, static_cast<uint8_t>(sim::SheetAction::kEdit),
                           {s.sheet_editing ? 1.0f : 0.0f, static_cast<float>(drag.influence),
                            static_cast<float>(drag.radius)}));
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
        save_project(start, loop_.volume(), s, s.custom_tool ? &loop_.tool() : nullptr, view(),
                     loop_.sheet().has_sheet() ? &loop_.sheet().surface() : nullptr);
    if (!saved) {
      report(saved, "");
      return saved;
    }
  }
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

void StationController::tick(int64_t now_ns) {
  if (recorder_.recording()) {
    if (Status st = recorder_.flush(); !st) status_ = "recording stopped: " + st.error().message();
  }
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
  auto tool = settings.custom_tool ? std::make_shared<core::Tool>(loop_.tool()) : nullptr;
  auto sheet = loop_.sheet().has_sheet()
                   ? std::make_shared<core::nurbs::NurbsSurface>(loop_.sheet().surface())
                   : nullptr;
  autosave_ = std::async(
      std::launch::async, [path = autosave_path(), volume, settings, tool, sheet, view = view()] {
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
