#pragma once
// The station without a window (DESIGN.md §1): device input and station
// commands in, sculpture and surface out. The live loop, `sculpt replay` and
// the tests all drive this one class, so a replay runs exactly the code a live
// session ran.
//
// Device buttons: button 0 presses the tool into the material while held;
// button 1 switches between add and subtract (leaving a ball brush). With a
// ball brush chosen (settings().brush), or smooth mode with the ball tool
// (core's smooth brush), a press collects the sampler's dabs as its path and
// applies the brush to the whole path when it ends: one undo step, the
// tool's radius as the ball's (half its size for other shapes), the hardness
// and strength settings, mirrored too when a mirror plane is set; grab uses
// the first and last sample. While the press goes on the brush is shown on
// the path so far (brush_preview.h), put back and shown again as the path
// grows, so the sculptor sees it work; what the press leaves is exactly the
// whole path's brush. Smooth mode with any other tool smooths dab by dab
// with the tool (the discrete-tools paper's smoothing). In touch mode
// (touch_mode.h) the tool rests on the material and button 0 sculpts only where the device pushes
// past the press threshold. A device that vanishes while pressed ends the stroke cleanly, and so
// does a tracker losing its target (its next pose re-anchors where the tool is: the tool never
// jumps).
//
// Thread safety: one thread (the main loop) calls everything.

#include <cstdint>
#include <future>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/sculpt/sculptor.h"
#include "sculpt/core/sculpt/stroke.h"
#include "sculpt/core/volume/volume.h"
#include "sculpt/hal/pose/pose_integrator.h"
#include "sculpt/hal/stroke/stroke_sampler.h"
#include "sculpt/hal/types/input_event.h"
#include "sculpt/sim/session/session.h"
#include "sculpt/station/app/brush_preview.h"
#include "sculpt/station/app/dab_stand_ins.h"
#include "sculpt/station/app/sheet_editor.h"
#include "sculpt/station/app/touch_mode.h"
#include "sculpt/station/settings/station_settings.h"

namespace sculpt::station {

/// The tool a shape and sizes describe (sizes are clamped to at least 0.5 voxel).
core::Tool make_tool(sim::ToolShape shape, float size_a_vox, float size_b_vox,
                     float hardness = 1.0f);
/// A block of `dims` voxels holding a slab of clay inset by `margin` voxels
/// on every side (a 2-voxel density ramp at its faces).
core::Volume clay_block(glm::ivec3 dims, int margin);
/// The diameter of that tool, voxels: what dab spacing is relative to.
float tool_size_vox(sim::ToolShape shape, float size_a_vox, float size_b_vox);

/// The core brush a press's path goes to: the ball brushes, and smoothing
/// (smooth mode with the ball tool).
enum class PathBrush : uint8_t { kSmooth, kClay, kFlatten, kInflate, kPinch, kGrab };
PathBrush path_brush_of(BallBrush brush);

/// A brush's stroke along `path` (at least one sample) on `volume` (the
/// one `sculptor` sculpts): the core brush (core/sculpt/*_brush.h) with a
/// ball of `radius_vox` (clamped to (0, core::kMaxBrushRadiusVox]),
/// `hardness` and `strength` (clamped to [0, 1]), its other options the
/// core's defaults (clay's layer, inflate's distance). With `mirror` the
/// brush then runs again along the path mirrored across that plane (where the
/// two overlap the brush applies twice). One undo step either way. Returns
/// the voxels changed (counted per pass).
int64_t path_brush_stroke(core::Volume& volume, core::Sculptor& sculptor, PathBrush brush,
                          std::span<const core::StrokeSample> path, float radius_vox,
                          float hardness, float strength,
                          std::optional<core::MirrorPlane> mirror = std::nullopt);
inline int64_t ball_brush_stroke(core::Volume& volume, core::Sculptor& sculptor, BallBrush brush,
                                 std::span<const core::StrokeSample> path, float radius_vox,
                                 float hardness, float strength,
                                 std::optional<core::MirrorPlane> mirror = std::nullopt) {
  return path_brush_stroke(volume, sculptor, path_brush_of(brush), path, radius_vox, hardness,
                           strength, mirror);
}
/// The voxels path_brush_stroke() may write (within the ball's reach of the
/// path and of its mirror image), clipped to `volume`.
core::Box path_brush_reach(const core::Volume& volume, std::span<const core::StrokeSample> path,
                           float radius_vox, std::optional<core::MirrorPlane> mirror);

/// What the last offset or closing (kMorphology) did: voxels inside the
/// surface (density above 127.5) in the box it worked on, before and after.
struct MorphologyResult {
  bool applied = false;  ///< false: no surface in the block, nothing changed
  int64_t inside_before = 0;
  int64_t inside_after = 0;
};

struct StationCounters {
  int64_t dabs = 0;
  int64_t strokes = 0;
  int64_t motion_samples = 0;
  int64_t undos = 0;
  int64_t redos = 0;
  int64_t disconnects = 0;
  int64_t sheet_grabs = 0;   ///< presses that grabbed the sheet
  int64_t sheet_misses = 0;  ///< presses in sheet editing that found no sheet near the tool
  /// A tracker lost its target (each loss ends the stroke).
  int64_t tracking_losses = 0;
  /// Path brushes shown on the path so far while a press went on.
  int64_t brush_previews = 0;
  /// Of those, smoothing previews that brushed only what the path's new
  /// samples reach (BrushPreview::extend) instead of the whole path again.
  int64_t brush_previews_extended = 0;
  /// Dabs shown by a stand-in before they were sculpted (dab_stand_ins.h).
  int64_t dabs_stood_in = 0;
};

class StationLoop {
 public:
  /// A device's buttons: 0 sculpts while held, 1 switches add and subtract,
  /// and this one is the clutch while held (a tracker's grip button).
  static constexpr int kClutchButton = 2;
  /// A custom tool at its scale (kToolScale) is at most this many voxels a
  /// side: a tool is rotated voxel by voxel at each new orientation.
  static constexpr int kMaxScaledToolEdge = 192;
  struct Options {
    glm::ivec3 volume_dims{256};
    uint8_t volume_fill = 0;
    /// > 0: start with a slab of clay filling the block but for this margin.
    int clay_margin = 0;
    /// Keep a level-0 mesh up to date after every input (for drawing and for
    /// the latency figure); off for the fastest possible replay.
    bool mesh = true;
    hal::PoseIntegratorConfig pose{};
    /// The undo history's memory budget: the oldest strokes go beyond it.
    size_t undo_max_bytes = core::UndoHistory::kDefaultMaxBytes;
    /// Show a brush press's path brush while it goes on (brush_preview.h);
    /// off where nobody looks (`sculpt replay`): the result is the same.
    bool preview_brushes = true;
    /// Offset and closing (kMorphology) compute their distance transforms
    /// on a worker thread, seconds for a big sculpture, and land when
    /// settled (settle()); every later input settles first, so the result
    /// is the same as at once. On in the window, whose drawing and steering
    /// go on meanwhile; off for replays.
    bool background_morphology = false;
    /// Strokes keep the voxels they store for take_stored_voxels(), so that
    /// a mesher need not decode those bricks again (core::SculptorOptions::
    /// hand_over_voxels). On in the window.
    bool hand_over_voxels = false;
  };
  explicit StationLoop(const Options& options);
  ~StationLoop();
  StationLoop(StationLoop&&) noexcept;
  StationLoop& operator=(StationLoop&&) noexcept;

  /// A station command (recorded in sessions, issued by the UI).
  void handle(const sim::Command& command);
  /// One normalised device event.
  void handle(const hal::InputEvent& event);
  /// Takes over an opened project's state; the undo history starts empty.
  /// `custom_tool` is the tool when settings.custom_tool, as it was made
  /// (custom_tool_base()): settings.tool_scale scales it again.
  void restore(std::unique_ptr<core::Volume> volume, const StationSettings& settings,
               std::optional<core::Tool> custom_tool,
               std::optional<core::nurbs::NurbsSurface> sheet = std::nullopt);
  /// Stops the stroke in progress (the UI lost the pointer, a device went).
  void release_stroke() { release(); }
  /// The tool in use (its reference, unrotated form).
  const core::Tool& tool() const { return *tool_; }
  /// The same, shared: never changed (a new tool is a new one), so another
  /// thread may read it after letting go of the loop (the window outlines
  /// a changed tool after its turn, the stand-ins march theirs aside).
  std::shared_ptr<const core::Tool> shared_tool() const { return tool_; }
  /// A custom tool as it was made, before settings().tool_scale resampled
  /// it into tool() (what a project keeps, so the scale replays exactly).
  const core::Tool& custom_tool_base() const { return custom_base_; }
  /// Moves on whenever the tool changes: a renderer remakes the tool's
  /// mesh when it moved, without comparing every voxel each frame.
  uint64_t tool_version() const { return tool_version_; }
  /// Diameter of the tool in use, voxels (what dab spacing is relative to).
  float tool_size() const;
  /// Re-meshes what changed since the last call; returns bricks meshed.
  int64_t update_mesh();

  const core::Volume& volume() const { return *volume_; }
  /// Moves on each time the volume is replaced (a new block, a project or a
  /// session start restored): a mirror of it starts again from a copy.
  uint64_t volume_generation() const { return volume_generation_; }
  const core::MeshCache& mesh() const { return mesh_; }
  const hal::ToolPose& pose() const { return integrator_.pose(); }
  const StationSettings& settings() const { return settings_; }
  const StationCounters& counters() const { return counters_; }
  bool pressed() const { return pressed_; }
  /// The clutch is held (the key's command or the device's third button).
  bool clutched() const { return integrator_.clutched(); }
  /// The clutch key is held, as the clutch commands last said.
  bool clutch_key_held() const { return clutch_key_; }
  const core::Sculptor& sculptor() const { return *sculptor_; }
  /// The voxels strokes stored since the last call (Options::hand_over_voxels).
  core::StoredVoxelsByBrick take_stored_voxels() {
    return sculptor_ ? sculptor_->take_stored_voxels() : core::StoredVoxelsByBrick{};
  }
  /// The tool rotation caches' counts over the loop's life (every volume's
  /// sculptor; bytes and entries: those held now).
  core::RotatedToolCacheStats rotation_cache_stats() const;
  const SheetEditor& sheet() const { return sheet_; }
  /// The last offset or closing as it landed (applied false while one is
  /// still computing: morphology_pending()).
  const MorphologyResult& last_morphology() const { return morphology_; }
  /// An offset or closing is computing on its worker (background_morphology).
  bool morphology_pending() const { return morphology_job_ != nullptr; }
  /// It has finished computing: settle() lands it without waiting.
  bool morphology_ready() const;
  /// Waits for an offset or closing computing in the background and lands
  /// it on the volume (one undo step); nothing when none is pending. Every
  /// handle() and restore() settles first.
  void settle();
  /// Dabs that add or carve the whole tool are published to `board` before
  /// they are sculpted, for the window to draw (dab_stand_ins.h); null:
  /// none. The board must outlive the loop's use of it.
  void show_stand_ins(DabStandIns* board);
  /// When the last stand-ins were published (hal::monotonic_ns()).
  int64_t stand_ins_published_ns() const { return stand_ins_ns_; }
  /// At `now_ns` (hal::monotonic_ns()), between polls of the devices:
  /// shows the press's ball-brush path again when dabs came that no
  /// preview shows and the last preview ended at least twice its own time
  /// ago. The dabs BrushPreview::due() leaves for later (the path's tail
  /// when the hand slows or stops) so show within about three previews'
  /// time, and previews take at most about a third of the sculpting thread.
  void catch_up_brush_preview(int64_t now_ns);
  /// Dabs of the press's ball-brush path that no preview shows yet (they
  /// show at the next preview, or when the press ends); 0 without one.
  int64_t dabs_not_yet_shown() const {
    if (brush_path_.empty()) return 0;
    return static_cast<int64_t>(brush_path_.size() - preview_.shown_samples());
  }
  /// Why the last sheet command or grab did nothing (empty if it worked).
  const std::string& sheet_problem() const { return sheet_problem_; }

 private:
  void new_volume(glm::ivec3 dims, uint8_t fill, int clay_margin);
  void apply_tool();
  // `tool` is the custom tool now, as made, at scale 1.
  void set_custom_tool(core::Tool tool, CustomToolSource source, core::Box region = {});
  // The custom tool at settings_.tool_scale into tool_.
  void scale_custom_tool();
  core::SculptorOptions sculptor_options() const;
  // Drops the sculptor, keeping its rotation cache counts.
  void retire_sculptor();
  void reset_sampler();
  void move_tool(const float* values, bool keep_stroke);
  void press();
  void release();
  void sculpt(const std::vector<hal::Dab>& dabs);
  // Finishes the press's swept stroke or brush path; its next sample starts
  // a new one at the last sample (same undo step for a swept stroke).
  void interrupt_stroke();
  // Applies the path brush to the path collected (nothing if none), after
  // putting back what its preview showed.
  void finish_brush();
  // Shows the path brush on the path so far (brush_preview.h).
  void show_brush_preview();
  // The path brush a dab now goes to, if any: the chosen ball brush, or
  // smoothing when smooth mode has the ball tool.
  std::optional<PathBrush> path_brush() const;
  // Whether the open swept stroke's mode, strength and accumulation are the
  // settings' (else a new sweep starts where the tool is).
  bool stroke_sculpts_as_set() const;
  // Whether a dab now adds (false) or carves (true) the tool's whole solid
  // where it lands, which a stand-in can show; nullopt: neither.
  std::optional<bool> stand_in_carves() const;
  // `dabs` and copies of the tool between them where the press sweeps it.
  std::vector<hal::Dab> stand_in_copies(const std::vector<hal::Dab>& dabs);
  void give_stand_ins_the_tool();
  void tool_moved();
  // Touch mode's half of a motion sample: the tool onto the proxy.
  void touch_moved(const hal::InputEvent& e);
  void sheet_command(const sim::Command& command);
  void morphology(const sim::Command& command);
  // An offset or closing: its inputs, result and (in the background) worker.
  struct MorphologyJob;
  void land(MorphologyJob& job);
  void sheet_into_material(float thickness_vox, bool add);
  void sheet_as_tool(float thickness_vox);
  void apply_clutch();

  Options options_;
  std::unique_ptr<core::Volume> volume_;
  uint64_t volume_generation_ = 0;
  uint64_t tool_version_ = 0;
  std::unique_ptr<core::Sculptor> sculptor_;
  // The rotation cache counts of the sculptors new volumes replaced.
  core::RotatedToolCacheStats retired_cache_stats_;
  // What the sculptor holds, kept for drawing; never null.
  std::shared_ptr<const core::Tool> tool_ = std::make_shared<const core::Tool>();
  core::Tool custom_base_;  // a custom tool as made (tool_ is it at tool_scale)
  core::MeshCache mesh_;
  hal::PoseIntegrator integrator_;
  hal::StrokeSampler sampler_;
  StationSettings settings_;
  StationCounters counters_;
  bool pressed_ = false;
  bool clutch_key_ = false;     // the clutch command: held
  bool clutch_button_ = false;  // the device's clutch button: held
  bool sheet_press_ = false;    // pressed_ went to the sheet (sheet editing), not to a stroke
  bool sheet_held_ = false;     // and grabbed it
  std::vector<hal::Dab> dabs_;
  // The press's swept stroke (stroke.h): between two of the sampler's dabs
  // the tool's swept volume, so a stroke leaves no scallop; none in smooth
  // mode, which places dabs. Restarted at its last sample when the mode or
  // strength changes mid-press (one undo step still).
  std::unique_ptr<core::SweptStroke> stroke_;
  core::StrokeOptions stroke_options_;
  core::StrokeSample stroke_last_;
  bool resume_stroke_ = false;
  // A path brush's press: the brush, strength and mirror it started with
  // and the path so far, applied by finish_brush() when the press ends or
  // any of them changes, and shown meanwhile by preview_.
  PathBrush brush_ = PathBrush::kClay;
  float brush_strength_ = 1.0f;
  std::optional<core::MirrorPlane> brush_mirror_;
  DabStandIns* stand_ins_ = nullptr;
  int64_t stand_ins_ns_ = 0;
  int64_t preview_ended_ns_ = 0;  // the last brush preview's end and time taken
  int64_t preview_took_ns_ = 0;
  // The ball the shown preview brushed with (radius, hardness, strength):
  // a preview extends it only with the same.
  glm::vec3 preview_ball_{-1.0f};
  std::optional<hal::Dab> stand_in_last_;             // the press's last dab stood in
  std::future<DabStandIns::ToolMesh> stand_in_tool_;  // being meshed for the board
  std::vector<std::future<DabStandIns::ToolMesh>> retired_marches_;  // for tools since replaced
  std::vector<core::StrokeSample> brush_path_;
  BrushPreview preview_;
  SheetEditor sheet_;
  TouchMode touch_;
  std::string sheet_problem_;
  MorphologyResult morphology_;
  std::unique_ptr<MorphologyJob> morphology_job_;  // computing in the background
};

}  // namespace sculpt::station
