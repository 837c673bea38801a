#pragma once
// Dab scripts (`sculpt stamp --dabs`): JSON Lines of sculpting operations,
// the scripting face of the discrete tools ("Discrete tools for virtual
// sculpture" §3). One object per line, each with an "op"; blank lines and
// lines starting with '#' are skipped:
//   {"op":"tool","shape":"sphere","radius":8}        also cube (edge), cylinder
//   (radius, height), ring (major, minor), cone (radius, height),
//   file (path, relative to the script), region (box [x0,y0,z0,x1,y1,z1] of
//   the volume as it is now: the sculpture becomes the tool)
//   {"op":"save_tool","path":"t.nrrd"}               the current tool, with pivot
//   {"op":"sampling","value":"trilinear"}            or "nearest"
//   {"op":"mirror","axis":"x","centre":63.5}         axis "off" disables
//   {"op":"begin"} ... {"op":"end"}                  a stroke (one undo step)
//   {"op":"dab","at":[x,y,z],"mode":"add","strength":1,"euler":[rx,ry,rz]}
//        mode add|subtract|union|difference|smooth (default add), strength in
//        [0, 1] (default 1), rotation as "euler" (degrees, extrinsic xyz) or
//        "quat" [w,x,y,z] (default none)
//   {"op":"undo"}, {"op":"redo"}
//   {"op":"stroke","path":[[x,y,z],...],"mode":"subtract","strength":0.5}
//        a swept stroke (core/sculpt/stroke.h) through the path's points:
//        mode add|subtract|union|difference (default add), strength in
//        [0, 1] (default 1), optional "quats" (one [w,x,y,z] per point),
//        "spacing" (voxels: the station's stroke sampler re-places the
//        samples along the path that far apart, as live input's) and
//        "accumulate" (true: the stroke builds up where it overlaps itself)
//   {"op":"clay","path":[[x,y,z],...],"radius":8,"hardness":0.5,"strength":1}
//        a ball brush (core/sculpt/*_brush.h) swept through the path: smooth
//        ("passes"), clay ("layer"), flatten, inflate ("distance"), pinch,
//        grab; every key but "op" and "path" optional (the brush's
//        defaults), any other key refused
// Every tool takes an optional "hardness" in [0, 1] (default 1, the hard
// edge; 0 a smooth bump: core::tool_density()).
// Every field is checked where it is read (docs/formats.md lists the
// limits); the whole script is read before anything is applied, and an
// error names the script, the line and the field.

#include <istream>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/base/result.h"
#include "sculpt/core/grid/box.h"
#include "sculpt/core/sculpt/clay_brush.h"
#include "sculpt/core/sculpt/flatten_brush.h"
#include "sculpt/core/sculpt/grab_brush.h"
#include "sculpt/core/sculpt/inflate_brush.h"
#include "sculpt/core/sculpt/pinch_brush.h"
#include "sculpt/core/sculpt/sculptor.h"
#include "sculpt/core/sculpt/smooth_brush.h"
#include "sculpt/core/sculpt/stroke.h"
#include "sculpt/core/tool/tool_rotation.h"
#include "sculpt/sim/session/command_limits.h"

namespace sculpt::station::dab_script {

/// Largest built-in tool size accepted, in voxels: the sessions' limit
/// (command_limits.h), so a script and a recording accept the same tools.
inline constexpr double kMaxToolSize = sim::kMaxToolSizeVox;

/// Largest tool grid edge accepted from a file or a region, in voxels: the
/// rotation cache indexes rows with 16-bit offsets, and a tool that large
/// would be a volume, not a tool.
inline constexpr int kMaxToolEdge = 1024;

/// A tool: a built-in `shape` of sizes a, b (voxels), a tool file at
/// `path`, or a `box` of the volume (shape "region").
struct ToolOp {
  std::string shape;
  double a = 0.0, b = 0.0;
  std::string path;
  core::Box box;
  double hardness = 1.0;
  /// "scale": the tool made this much larger or smaller (core::scale_tool).
  double scale = 1.0;
};
struct SaveToolOp {
  std::string path;
};
struct SamplingOp {
  core::Sampling sampling;
};
struct MirrorOp {
  std::optional<core::MirrorPlane> plane;
};
struct StrokeOp {
  bool begin;
};
struct UndoOp {
  bool redo;
};
/// Most points a "stroke" line may give, and most samples its "spacing" may
/// place: a stroke across the largest volume at a tenth of a voxel.
inline constexpr size_t kMaxStrokePoints = 100000;
inline constexpr double kMaxStrokeSamples = 1000000.0;
/// A swept stroke: its points (orientations from "quats", else none), and
/// the sampler's spacing in voxels (0: the points are the samples).
struct SweepOp {
  std::vector<core::StrokeSample> path;
  core::StrokeOptions options;
  double spacing_vox = 0.0;
};
/// A ball brush's stroke: its path (positions only) and the brush, named by
/// its options' type.
struct BrushOp {
  std::vector<core::StrokeSample> path;
  std::variant<core::SmoothBrushOptions, core::ClayBrushOptions, core::FlattenBrushOptions,
               core::InflateBrushOptions, core::PinchBrushOptions, core::GrabBrushOptions>
      options;
};
using Op = std::variant<ToolOp, SaveToolOp, SamplingOp, MirrorOp, StrokeOp, core::Dab, UndoOp,
                        SweepOp, BrushOp>;

/// One operation and the script line it came from (1-based).
struct Line {
  int number = 0;
  Op op;
};

/// The operations of a script read from `in`, for a volume of `volume_dims`
/// voxels; errors are "NAME:LINE: what is wrong".
Result<std::vector<Line>> parse(std::istream& in, const std::string& name, glm::ivec3 volume_dims);
/// parse() of the file at `path`.
Result<std::vector<Line>> read(const std::string& path, glm::ivec3 volume_dims);

}  // namespace sculpt::station::dab_script
