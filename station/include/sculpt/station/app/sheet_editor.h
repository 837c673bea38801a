#pragma once
// The station's NURBS sheet (La Greca, Raffin & Gesquière, "Punctual
// constraint resolution and deformation path on NURBS"): a free-form surface
// next to the voxel material that the device grabs and drags.
//
// grab() picks the sheet's point closest to the tool tip (point inversion),
// refines the sheet around it when the influence is a zone, and starts a live
// path deformation: while the device moves, each new tip position (once it
// has moved `path_step_vox` from the last) is a path point and the sheet
// follows it step by step (§4.3); the tip at release() ends the path. release() fits a cubic curve
// to the device's path by least squares (A9.7) and re-runs the path deformation along that curve
// from the sheet as it was at grab(), so the result is the paper's deformation along a smooth path,
// its last step exact. A path too short to fit keeps the live result, finished exactly.
//
// Sheet edits have their own undo history (the station's Undo reaches it
// while sheet editing is on). Everything is double precision and single
// threaded, so a replayed session deforms the sheet bit for bit as the live
// one did.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/base/result.h"
#include "sculpt/core/mesh/mesh.h"
#include "sculpt/core/nurbs/nurbs_surface.h"
#include "sculpt/core/nurbs/path_deformation.h"
#include "sculpt/core/nurbs/surface_tessellator.h"
#include "sculpt/station/settings/station_settings.h"

namespace sculpt::station {

class SheetEditor {
 public:
  /// A flat bicubic sheet of `points` x `points` control points, `size`
  /// voxels square, centred at `centre`, normal to axis `normal_axis`.
  static core::nurbs::NurbsSurface flat(glm::dvec3 centre, double size, int points,
                                        int normal_axis);

  bool has_sheet() const { return surface_.has_value(); }
  /// The sheet now (during a drag: as deformed so far). Only when has_sheet().
  const core::nurbs::NurbsSurface& surface() const { return *surface_; }
  /// Its tessellation, voxel units (empty without a sheet).
  const core::Mesh& mesh() const;
  /// Changes whenever the sheet or its mesh does (for GPU uploads).
  uint64_t version() const { return version_; }

  /// Replaces the sheet (undoable); std::nullopt removes it.
  void set(std::optional<core::nurbs::NurbsSurface> surface);
  /// Replaces the sheet and forgets the undo history (an opened project).
  void reset(std::optional<core::nurbs::NurbsSurface> surface);

  /// Starts dragging the sheet point closest to `tip`; fails, saying why,
  /// when there is no sheet or it is further than options.reach_vox.
  Status grab(glm::dvec3 tip, const SheetDragOptions& options);
  bool dragging() const { return drag_.has_value(); }
  /// The tip moved (ignored when not dragging).
  void drag(glm::dvec3 tip);
  /// Ends the drag: the fitted path's deformation (see the file comment).
  void release();
  /// The grabbed (u, v) and where S(u, v) should be now (while dragging).
  std::optional<glm::dvec3> grabbed_target() const;
  /// Path points taken so far in the current drag, and steps applied live.
  int path_points() const { return drag_ ? static_cast<int>(drag_->path.size()) : 0; }
  /// |S(u,v) - target| after the last finished drag (0 before any).
  double last_residual() const { return last_residual_; }

  bool undo();
  bool redo();

 private:
  struct Drag {
    core::nurbs::NurbsSurface before;  // the sheet at grab()
    std::vector<double> influence;     // f for `before` (refined if a zone)
    core::nurbs::NurbsSurface start;   // `before` refined: what the path deforms
    double u = 0, v = 0;
    glm::dvec3 tip_at_grab{0.0};
    std::vector<glm::dvec3> path;  // the dragged point's path, path[0] = S(u, v)
    glm::dvec3 latest{0.0};        // where the tip now puts it (path.back() or nearer than a step)
    core::nurbs::PathDeformation live;
    SheetDragOptions options;
  };
  using History = std::vector<std::optional<core::nurbs::NurbsSurface>>;
  void remember(std::optional<core::nurbs::NurbsSurface> before);
  // Undo and redo: the newest sheet of `from` becomes the sheet, the sheet
  // goes to `to`.
  bool step(History& from, History& to);
  void retessellate();

  std::optional<core::nurbs::NurbsSurface> surface_;
  std::optional<core::nurbs::SurfaceTessellator> tessellator_;
  std::optional<Drag> drag_;
  // Undo: the sheet before each edit (nullopt: there was none); redo likewise.
  History undo_, redo_;
  uint64_t version_ = 0;
  double last_residual_ = 0.0;
};

}  // namespace sculpt::station
