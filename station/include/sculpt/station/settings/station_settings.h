#pragma once
// What the user has chosen: the tool, the mode, the dab spacing, the sheet's
// drag options (the UI panel's state). Its own header below app/ and
// project/: a project saves these and the station loop applies them, so
// neither of those needs the other to know what a setting is.

#include <cstdint>
#include <optional>

#include "sculpt/core/grid/box.h"
#include "sculpt/core/sculpt/sculptor.h"
#include "sculpt/hal/pose/tracker_mapping.h"
#include "sculpt/sim/session/session.h"

namespace sculpt::station {

/// How far a grab reaches along the sheet (the localisation f of §4.2).
enum class SheetInfluence : uint8_t {
  kNatural,   ///< f = R_ij(u,v): the smallest change
  kGaussian,  ///< natural spread by a Gaussian of `radius` control points
  kZone,      ///< a circle of `radius` (parameter units) around the grab, refined
};

struct SheetDragOptions {
  SheetInfluence influence = SheetInfluence::kGaussian;
  double radius = 2.0;
  /// Path points are at least this far apart (voxels).
  double path_step_vox = 1.0;
  /// The tip must be this close to the sheet to grab it (voxels).
  double reach_vox = 6.0;
};

/// The ball brushes (core/sculpt/*_brush.h) offered next to the modes: a
/// press collects its path and the brush applies to all of it, as one undo
/// step, when the press ends. Same order as sim::SculptModeId from kClay.
enum class BallBrush : uint8_t { kClay, kFlatten, kInflate, kPinch, kGrab };
inline constexpr uint8_t kBallBrushCount = 5;

/// Where a custom tool came from (the panel names it; projects do not keep
/// it: an opened project's is kFile).
enum class CustomToolSource : uint8_t { kRegion, kSheet, kFile };

/// What the user has chosen (the UI panel's state).
struct StationSettings {
  sim::ToolShape shape = sim::ToolShape::kSphere;
  /// The tool is not `shape` but a region of the material (tool_from_region)
  /// or the NURBS sheet's shell; it stays the tool until another is chosen.
  bool custom_tool = false;
  core::Box custom_region;  ///< the material's region it came from, voxels (empty: not a region)
  CustomToolSource custom_source = CustomToolSource::kFile;
  /// The custom tool's scale from the size it was made at (core::scale_tool;
  /// 1: as made), in [0.125, 8].
  float tool_scale = 1.0f;
  float size_a_vox = 8.0f;  ///< sphere radius, cube edge, cylinder/cone radius, ring major radius
  float size_b_vox = 0.0f;  ///< cylinder/cone height, ring minor radius
  core::SculptMode mode = core::SculptMode::kAdd;
  /// Set: presses apply this brush (ball of the tool's radius, the hardness
  /// and strength below) instead of `mode`.
  std::optional<BallBrush> brush;
  float strength = 1.0f;
  /// The built-in tools' hardness: 1 a hard edge, 0 a smooth bump
  /// (core::Tool::hardness; a custom tool keeps its own).
  float hardness = 1.0f;
  float spacing = 0.25f;  ///< dab spacing, fraction of the tool's size
  /// Swept strokes build up where they overlap themselves
  /// (core::StrokeOptions::accumulate); off, the strength applies once.
  bool accumulate = false;
  std::optional<core::MirrorPlane> mirror;
  /// Device presses grab the NURBS sheet instead of sculpting, and Undo and
  /// Redo act on the sheet.
  bool sheet_editing = false;
  /// Touch mode (app/touch_mode.h): the tool stops on the material and
  /// presses in as the device pushes.
  bool touch = false;
  SheetDragOptions sheet_drag;
  /// How a tracker's motion maps to the sculpture (scale and axes).
  hal::TrackerCalibration tracker;
};

}  // namespace sculpt::station
