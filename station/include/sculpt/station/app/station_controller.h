#pragma once
// The station as the user drives it, without any GL: what the panel's
// buttons, the keyboard shortcuts, the ordinary mouse and the 3D mouse do.
// The window (station/window) only turns GLFW and ImGui events into calls of
// this class and draws its state, so all of the UI's logic is tested here.
//
// Every change of a setting becomes a sim::Command handed to the StationLoop
// (and to the recorder when recording), so a recorded session replays what
// the user did through the panel, not only the device's motion.
//
// Thread safety: one thread (the main loop), except raw_report(), which the
// device reader threads call.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <future>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>

#include "sculpt/hal/input/device_reader.h"
#include "sculpt/hal/types/device_info.h"
#include "sculpt/station/app/input_statistics.h"
#include "sculpt/station/app/session_recorder.h"
#include "sculpt/station/app/session_replay.h"
#include "sculpt/station/app/station_loop.h"
#include "sculpt/station/project/project_file.h"
#include "sculpt/station/render/software_renderer.h"
#include "sculpt/station/view/lod_selector.h"
#include "sculpt/station/view/orbit_camera.h"
#include "sculpt/station/view/surface_mesher.h"

namespace sculpt::station {

/// What the 3D mouse moves.
enum class DeviceTarget { kTool, kCamera };

/// The actions keyboard shortcuts reach (the panel reaches them too).
enum class Action {
  kUndo,
  kRedo,
  kToggleAddSubtract,
  kSmooth,
  /// The ball brushes (StationSettings::brush): a press applies the brush to
  /// its whole path when it ends.
  kBrushClay,
  kBrushFlatten,
  kBrushInflate,
  kBrushPinch,
  kBrushGrab,
  /// Swept strokes build up where they overlap themselves, or not.
  kToggleAccumulate,
  kToolSphere,
  kToolCube,
  kToolCylinder,
  kToolRing,
  kToolCone,
  kToolBigger,
  kToolSmaller,
  kStronger,
  kWeaker,
  kToggleMirror,
  kToggleDeviceTarget,
  kToggleTouch,  ///< touch mode (touch_mode.h)
  /// The tool to the block's centre, upright: a tracker held where the
  /// sculpture's centre should be is calibrated there (it re-anchors).
  kCentreTool,
  kToggleRecording,
  kSave,
  kExportMesh,
  kUseSculptureAsTool,
  /// Shows the tool region (tool_region()), from the material's bounds (or
  /// around the tool when there is none), or hides it.
  kToggleToolRegion,
  kUseRegionAsTool,
  /// A new block (new_block_options()) in place of the sculpture. Not
  /// undoable: the window asks first.
  kNewBlock,
  /// The sculpture's surface moved by offset_vox() / closed by
  /// closing_radius_vox() (Jones & Satherley §4.2), one undo step each.
  kOffsetSculpture,
  kCloseSculpture,
  kHypertexture,
  kFrameView,
  kTurnToolLeft,  ///< about the view's vertical axis
  kTurnToolRight,
  kTiltToolUp,  ///< about the view's horizontal axis
  kTiltToolDown,
  kNewSheet,
  kRemoveSheet,
  kToggleSheetEditing,
  kSheetAddToMaterial,
  kSheetSubtractFromMaterial,
  kSheetAsTool,
  kExportSheet,
};

/// What fills a new block.
enum class BlockFill : uint8_t { kEmpty, kFull, kClay };

/// The panel's new block: its size and what fills it.
struct NewBlockOptions {
  glm::ivec3 dims{256};
  BlockFill fill = BlockFill::kEmpty;
};

struct DeviceStatus {
  bool connected = false;
  std::string name;
  std::string backend;
  double report_rate_hz = 0;  ///< motion samples per second, last second
  int battery_percent = -1;   ///< -1: the device does not report one
  bool charging = false;
};

struct ControllerOptions {
  StationLoop::Options loop;
  /// Where Save writes and Open reads by default; the autosave sits beside
  /// it as PROJECT.autosave.
  std::filesystem::path project = "sculpture.sculpt";
  std::filesystem::path mesh_export = "sculpture.ply";
  /// How far Export mesh may move the surface to make fewer triangles,
  /// voxels (as `sculpt mesh --max-error`; the surface stays closed); 0:
  /// every triangle of the full-detail surface.
  float mesh_export_max_error = 0.0f;
  std::filesystem::path recording = "recording.scs";
  /// Export sheet writes STEM.json (NURBS), STEM.obj (free-form NURBS) and
  /// STEM.ply (its mesh).
  std::filesystem::path sheet_export = "sheet";
  /// The tool library: where Save tool writes and the panel lists tool files.
  std::filesystem::path tool_folder = "tools";
  /// Autosave interval, seconds (0: never).
  double autosave_seconds = 5.0;
  /// The input.conf the sensitivity and deadzone settings are saved to.
  std::string normalizer_config_path;
  /// Dabs that add the tool are published as stand-ins before they are
  /// sculpted (stand_ins(), dab_stand_ins.h): on where a window draws them.
  bool stand_ins = false;
};

class StationController {
 public:
  explicit StationController(ControllerOptions options);
  ~StationController();

  StationLoop& loop() { return loop_; }
  const StationLoop& loop() const { return loop_; }
  OrbitCamera& camera() { return camera_; }
  const OrbitCamera& camera() const { return camera_; }
  LodSelector& lod() { return lod_; }
  const ControllerOptions& options() const { return options_; }
  ControllerOptions& options() { return options_; }

  // --- settings and actions (each a command, recorded) -----------------
  void command(const sim::Command& command, int64_t now_ns);
  /// A command stamped with `t_ns` in the recording as it is.
  void command_at(const sim::Command& command, int64_t t_ns);
  /// A force device's loop record (haptics/haptic_recording.h), kept when
  /// recording, in order with the commands.
  void record_haptic(const sim::HapticRecord& record, int64_t now_ns) {
    if (recorder_.recording()) recorder_.haptic(record, stamp(now_ns));
  }
  void set_tool(sim::ToolShape shape, float size_a_vox, float size_b_vox, int64_t now_ns);
  /// A mode (and no brush), or a ball brush (the mode kept for later).
  void set_mode(core::SculptMode mode, int64_t now_ns);
  void set_brush(BallBrush brush, int64_t now_ns);
  /// Swept strokes build up where they overlap themselves (on) or apply
  /// their strength once (off).
  void set_accumulate(bool on, int64_t now_ns);
  void set_strength(float strength, int64_t now_ns);
  /// The built-in tools' hardness in [0, 1] (a new tool: ends a stroke).
  void set_hardness(float hardness, int64_t now_ns);
  void set_spacing(float spacing, int64_t now_ns);
  /// axis 0..2 mirrors across the block's middle plane on that axis.
  void set_mirror(std::optional<int> axis, int64_t now_ns);
  /// Touch mode (touch_mode.h): the tool rests on the material and presses
  /// in as the device pushes; for devices without force output.
  void set_touch(bool on, int64_t now_ns);
  /// The clutch (held: the device moves without the tool; let go: a tracker
  /// re-anchors where the tool is). Recorded only when it changes.
  void set_clutch(bool held, int64_t now_ns);
  /// A tracker's scale and axes (hal::TrackerCalibration); it re-anchors.
  void set_tracker_calibration(const hal::TrackerCalibration& calibration, int64_t now_ns);
  void undo(int64_t now_ns);
  void redo(int64_t now_ns);
  /// The material's bounding box becomes the tool (false, with the reason
  /// in status(), when there is no material or it is too big for a tool).
  bool use_sculpture_as_tool(int64_t now_ns);
  /// The box the panel picks a tool from (voxels, half-open; drawn as a
  /// wireframe while set). A UI state, not recorded: only the tool made of
  /// it is (kToolFromRegion).
  const std::optional<core::Box>& tool_region() const { return tool_region_; }
  /// The region set to `box`, clamped to the block (kept even when empty, so
  /// the panel can move a corner through it; Use region as tool says so).
  void set_tool_region(const core::Box& box);
  /// The region from the material's bounding box (false, with the reason in
  /// status(), when there is no material).
  bool tool_region_from_material();
  /// The region a cube of the tool's size (at least 8 voxels) around it.
  void tool_region_around_tool();
  void clear_tool_region() { tool_region_.reset(); }
  /// The material in the region becomes the tool (false, with the reason in
  /// status(): no region, an empty one, one over kMaxToolEdge a side, or
  /// one with no material in it).
  bool use_region_as_tool(int64_t now_ns);
  /// A custom tool (a region, the sculpture, the sheet's shell, a file) at
  /// `factor` times the size it was made at, resampled (core::scale_tool;
  /// factor clamped to [0.125, 8]). False, with the reason in status(), for
  /// a built-in tool (its sizes scale it) or a result over
  /// StationLoop::kMaxScaledToolEdge voxels a side.
  bool set_tool_scale(float factor, int64_t now_ns);
  /// The sculpture replaced by a new block of `block.dims` voxels (each side
  /// in [kMinBlockSide, kMaxBlockSide]), empty, full (density 255) or a slab
  /// of clay a quarter of the smallest side in from every side: the session
  /// command kVolume. The undo history starts again (nothing to undo back
  /// to the old sculpture: the panel confirms first). False, with the reason
  /// in status(), for a size out of range.
  bool new_block(const NewBlockOptions& block, int64_t now_ns);
  /// The sculpture's surface moved `by_vox` voxels along its normals
  /// (outward when positive) on its sub-voxel distance field, as `sculpt
  /// offset`; or closed (its gaps and dents narrower than twice the radius
  /// filled), as `sculpt close`. One undo step; the session command
  /// kMorphology. False, with the reason in status(), when there is no
  /// surface (an empty or solid block) or the distance is out of range
  /// ([-64, 64] voxels, a radius above 0).
  /// With the loop's background_morphology (the window) they return at
  /// once, the status saying they compute, and land_morphology() lands them.
  bool offset_sculpture(float by_vox, int64_t now_ns);
  bool close_sculpture(float radius_vox, int64_t now_ns);
  /// Lands an offset or closing computed in the background once it is
  /// ready (waiting for it when `wait`) and says so in status(); returns
  /// whether none is computing any more (the sculpting thread holds later
  /// input until then).
  bool land_morphology(bool wait = false);
  /// Called before a command from the UI (command(), open()) while an offset
  /// or closing computes: whoever holds input back meanwhile (InputHub)
  /// sculpts it first, so the command comes after it, as its time says.
  void set_input_barrier(std::function<void()> barrier) { input_barrier_ = std::move(barrier); }
  /// The panel's distances for the two (and their keys').
  float& offset_vox() { return offset_vox_; }
  float& closing_radius_vox() { return closing_radius_vox_; }
  NewBlockOptions& new_block_options() { return new_block_; }
  static constexpr int kMinBlockSide = 8;
  static constexpr int kMaxBlockSide = 1024;
  /// A tool file (.nrrd or .vdb with a pivot, core::read_tool_file) as the
  /// tool; its voxels go into the session (kToolVoxels). False, with one
  /// status line, for a missing or broken file or one over
  /// StationLoop::kMaxScaledToolEdge voxels a side.
  bool load_tool(const std::filesystem::path& path, int64_t now_ns);
  /// A closed mesh (OBJ, PLY, STL, GLB: core::read_mesh_file) voxelized as
  /// `sculpt voxelize --size edge_vox` does (its longest side edge_vox - 5
  /// voxels, centred) and made the tool; as load_tool otherwise. edge_vox in
  /// [8, kMaxScaledToolEdge].
  bool import_mesh_as_tool(const std::filesystem::path& path, int edge_vox, int64_t now_ns);
  /// The tool in use (built-in or custom, at its scale) as a tool file.
  Status save_tool(const std::filesystem::path& path);
  /// The tool files (.nrrd, .vdb) in `folder`, sorted by name, with a small
  /// picture of each (the software renderer's, `thumbnail_px` square); files
  /// that do not read as tools are left out and counted.
  struct ToolFileEntry {
    std::filesystem::path path;
    glm::ivec3 dims{0};
    RgbImage thumbnail;
  };
  struct ToolLibrary {
    std::vector<ToolFileEntry> tools;
    int unreadable = 0;
  };
  static ToolLibrary scan_tool_library(const std::filesystem::path& folder, int thumbnail_px = 48);
  /// The largest region or sculpture that becomes a tool, voxels a side: a
  /// tool is rotated voxel by voxel at every new orientation, so it must
  /// stay small next to the block.
  static constexpr int kMaxToolEdge = 96;
  /// Points the camera at the material (its bounding box), as "frame
  /// selected" does; an empty block is framed whole. Not recorded.
  void frame_sculpture();
  /// Bakes a hypertexture skin (distance-field noise, Jones & Satherley
  /// §4.3) into the surface around the tool, over the tool's size.
  void hypertexture(int64_t now_ns);
  /// Turns the tool by `angle_rad` about `axis` (world, unit): the keyboard's
  /// way to turn it; a stroke in progress goes on.
  void turn_tool(glm::vec3 axis, float angle_rad, int64_t now_ns);

  // --- the NURBS sheet (SheetEditor; each a kSheet command) -------------
  /// A new flat sheet through the tool, facing the camera.
  void new_sheet(int64_t now_ns);
  void remove_sheet(int64_t now_ns);
  /// Presses of the device or mouse grab the sheet instead of sculpting.
  void set_sheet_editing(bool on, int64_t now_ns);
  void set_sheet_influence(SheetInfluence influence, float radius, int64_t now_ns);
  /// The sheet's shell, `thickness_vox` thick, into the material.
  bool sheet_into_material(bool add, int64_t now_ns);
  bool sheet_as_tool(int64_t now_ns);
  Status export_sheet(const std::filesystem::path& stem);
  float sheet_thickness() const { return sheet_thickness_; }
  void set_sheet_thickness(float vox) { sheet_thickness_ = std::clamp(vox, 0.5f, 64.0f); }

  /// Runs a shortcut's action; false when it failed (see status()).
  bool perform(Action action, int64_t now_ns);

  /// Shade with normals from the distance field's gradient (Jones &
  /// Satherley) instead of the density's: a view setting, not recorded.
  bool distance_normals() const { return distance_normals_; }
  void set_distance_normals(bool on) { distance_normals_ = on; }

  DeviceTarget device_target() const { return device_target_; }
  void set_device_target(DeviceTarget target) { device_target_ = target; }

  // --- input -------------------------------------------------------------
  /// Everything the device readers delivered since the last frame, with the
  /// station commands a sim device played meanwhile (their times in its
  /// clock), applied in time order among its events.
  void device_frame(const hal::InputFrame& frame, int64_t now_ns,
                    std::span<const std::pair<int64_t, sim::Command>> device_commands = {});
  /// The ordinary mouse moved the tool to `position` (voxels); while the
  /// pointer is down, the move sculpts.
  void pointer_move(glm::vec3 position, int64_t now_ns);
  void pointer_down(int64_t now_ns);
  void pointer_up(int64_t now_ns);
  /// The device reader's count of motion samples so far (for the report
  /// rate the panel shows).
  void reader_samples(int64_t motion_samples, int64_t now_ns);
  /// A raw device event for the recording (reader threads).
  void raw_report(const hal::RawEvent& event);

  void set_device(const hal::DeviceInfo& info, const std::string& normalizer_text);

  // --- after input ------------------------------------------------------
  /// Re-meshes what changed (the loop's own mesh, on this thread) and notes
  /// the latency of every dab made since the previous call (report time to
  /// mesh ready). Returns bricks meshed.
  int64_t update_mesh(int64_t now_ns);
  /// The window's way, meshing on another thread (SurfaceMesher): the dabs
  /// made so far went to the mesher as change `change`...
  void surface_submitted(uint64_t change, int64_t now_ns);
  /// ...and the meshes of every change up to `change` were ready at
  /// `ready_ns` (up to `full_detail_change` at full detail): the latencies
  /// of their dabs (report to first mesh, and to full detail).
  void surface_ready(uint64_t change, uint64_t full_detail_change, int64_t ready_ns);
  /// The same for each change a mesher's delta says is ready, oldest first.
  void surface_ready(const SurfaceDelta& delta) {
    for (const SurfaceDelta::Readiness& r : delta.readiness)
      surface_ready(r.change, r.full_detail_change, r.ready_ns);
  }
  /// Latency of the last few hundred dabs, and of all of them.
  LatencyStats recent_latency() const { return stats_.recent_latency(); }
  LatencyStats session_latency() const { return stats_.session_latency(); }
  LatencyStats full_detail_latency() const { return stats_.full_detail_latency(); }
  LatencyStats first_picture_latency() const { return stats_.first_picture_latency(); }
  std::span<const InputStatistics::SlowDab> slowest_dabs() const { return stats_.slowest(); }
  /// The stand-ins of dabs not yet meshed (ControllerOptions::stand_ins);
  /// safe from any thread without mutex().
  DabStandIns& stand_ins() { return stand_ins_; }
  const DabStandIns& stand_ins() const { return stand_ins_; }
  const DeviceStatus& device_status() const { return device_; }

  // --- files ---------------------------------------------------------------
  Status save(const std::filesystem::path& path);
  Status open(const std::filesystem::path& path);
  Status export_mesh(const std::filesystem::path& path);
  Status start_recording(const std::filesystem::path& path, int64_t now_ns);
  Status stop_recording();
  bool recording() const { return recorder_.recording(); }
  /// Why the last recording stopped by itself (a write failed); empty if
  /// it did not.
  const std::string& recording_error() const { return recording_error_; }
  /// Periodic work: the recording's flush, the autosave when due.
  void tick(int64_t now_ns);
  /// Waits for an autosave in flight (tests, shutdown).
  void finish_autosave();
  std::filesystem::path autosave_path() const;
  int64_t autosaves() const { return autosaves_; }

  /// Saves sensitivity (one factor for all axes) and deadzone to the
  /// normaliser config file; they apply to devices opened afterwards.
  Status save_input_settings(float sensitivity, float deadzone);

  /// One line for the status bar: what the last action did or why it failed.
  const std::string& status() const { return status_; }

 private:
  bool report(const Status& status, const std::string& done);
  void camera_motion(const hal::InputEvent& e);
  // When event e's report came, on this machine's clock: what latencies count from.
  static int64_t report_time(const hal::InputEvent& e, int64_t now_ns);
  // The dabs made since `before` came from a report read at `t_ns`.
  void note_dabs(const StationCounters& before, int64_t t_ns);
  ProjectView view() const;
  // Starts an autosave on another thread when one is due (projects file).
  void autosave_if_due(int64_t now_ns);
  std::vector<sim::Command> opening_commands(bool with_block) const;
  bool morphology(bool close, float by_vox, int64_t now_ns);
  // The status of the offset or closing that landed last.
  bool morphology_status(bool close, float by_vox);
  // Before a UI command while an offset or closing computes: the input
  // barrier (the held reports go first).
  void let_held_input_go();
  // `tool` (from `what`: a file's name) as the tool, if it fits.
  bool give_tool(const core::Tool& tool, const std::string& what, int64_t now_ns);
  // The material in `box` (clamped) as the tool; `what` names it in messages.
  bool tool_from_box(core::Box box, const std::string& what, int64_t now_ns);

  ControllerOptions options_;
  StationLoop loop_;
  DabStandIns stand_ins_;
  OrbitCamera camera_;
  LodSelector lod_;
  DeviceTarget device_target_ = DeviceTarget::kTool;
  bool distance_normals_ = false;
  SessionRecorder recorder_;
  DeviceStatus device_;
  hal::DeviceInfo device_info_;
  std::string normalizer_text_;
  std::string status_;
  // An offset or closing computing in the background, for its status.
  struct Landing {
    bool close = false;
    float by = 0.0f;
  };
  std::optional<Landing> landing_;
  std::function<void()> input_barrier_;
  std::string recording_error_;

  // A command's time in a recording: just after the newest report processed
  // before it, so the recording orders it among the reports as the station
  // applied it (and in the device's own clock, which for a sim device is its
  // session's). Before any report: 0 with a device, else `now_ns`.
  int64_t stamp(int64_t now_ns) const;
  bool has_device_ = false;
  int64_t processed_t_ns_ = std::numeric_limits<int64_t>::min();
  bool pointer_down_ = false;
  InputStatistics stats_;
  uint64_t own_change_ = 0;  // update_mesh()'s change numbers
  int64_t last_camera_t_ns_ = 0;

  // Autosave: what the volume was at the last save, and the save in flight.
  uint64_t saved_generation_ = 0;
  uint64_t generation_ = 0;
  int64_t last_autosave_ns_ = 0;
  int64_t autosaves_ = 0;
  int hypertextures_ = 0;  // each gets its own noise
  float sheet_thickness_ = 3.0f;
  uint64_t sheet_version_ = 0;  // the sheet's version at the last update_mesh()
  std::future<Status> autosave_;
  std::optional<core::Box> tool_region_;
  NewBlockOptions new_block_;
  float offset_vox_ = 1.0f;
  float closing_radius_vox_ = 2.0f;
};

}  // namespace sculpt::station
