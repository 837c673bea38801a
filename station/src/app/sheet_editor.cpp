#include "sculpt/station/app/sheet_editor.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

#include "sculpt/core/nurbs/curve_fitting.h"
#include "sculpt/core/nurbs/influence.h"
#include "sculpt/core/nurbs/parameter_zone.h"
#include "sculpt/core/nurbs/point_inversion.h"

namespace sculpt::station {
namespace nurbs = core::nurbs;
namespace {

// The station's sheet mesh: about this many cells a side, whatever the
// refinement (SurfaceTessellator::with_cells).
constexpr int kSheetCells = 64;
// Undo keeps this many sheet edits (a sheet is a few kilobytes).
constexpr size_t kUndoDepth = 256;
// Live steps the thresholds s(k) are spread over: a drag of a hundred voxels
// at one point per voxel.
constexpr int kExpectedLiveSteps = 100;
// A zone needs this many control points inside it to bend smoothly (§4.2).
constexpr int kZoneMinPoints = 16;

std::vector<double> influence_for(const nurbs::NurbsSurface& s, double u, double v,
                                  const SheetDragOptions& o) {
  if (o.influence == SheetInfluence::kNatural) return nurbs::natural_influence(s, u, v);
  return nurbs::gaussian_influence(s, u, v, std::max(o.radius, 0.0));
}

}  // namespace

nurbs::NurbsSurface SheetEditor::flat(glm::dvec3 centre, double size, int points, int normal_axis) {
  points = std::clamp(points, 4, 64);
  nurbs::NurbsSurface s = nurbs::flat_sheet(points, points, 3, 3, size, size);
  // flat_sheet lies in z = 0 over [0, size]^2: centre it, then turn its
  // normal onto the chosen axis (a cyclic permutation keeps it right-handed).
  const int a = std::clamp(normal_axis, 0, 2);
  for (glm::dvec3& p : s.points) {
    const glm::dvec3 q(p.x - 0.5 * size, p.y - 0.5 * size, 0.0);
    glm::dvec3 r;
    r[(a + 1) % 3] = q.x;
    r[(a + 2) % 3] = q.y;
    r[a] = q.z;
    p = centre + r;
  }
  return s;
}

const core::Mesh& SheetEditor::mesh() const {
  static const core::Mesh kEmpty;
  return tessellator_ ? tessellator_->mesh() : kEmpty;
}

void SheetEditor::remember(std::optional<nurbs::NurbsSurface> before) {
  undo_.push_back(std::move(before));
  if (undo_.size() > kUndoDepth) undo_.erase(undo_.begin());
  redo_.clear();
}

void SheetEditor::retessellate() {
  if (surface_) {
    tessellator_ = nurbs::SurfaceTessellator::with_cells(*surface_, kSheetCells, kSheetCells);
  } else {
    tessellator_.reset();
  }
  ++version_;
}

void SheetEditor::set(std::optional<nurbs::NurbsSurface> surface) {
  if (drag_) release();
  remember(std::move(surface_));
  surface_ = std::move(surface);
  retessellate();
}

void SheetEditor::reset(std::optional<nurbs::NurbsSurface> surface) {
  drag_.reset();
  undo_.clear();
  redo_.clear();
  surface_ = std::move(surface);
  retessellate();
}

Status SheetEditor::grab(glm::dvec3 tip, const SheetDragOptions& options) {
  if (!surface_) return Error("there is no sheet to grab");
  if (drag_) release();
  const nurbs::SurfacePoint hit = nurbs::closest_point(*surface_, tip);
  if (!(hit.distance <= options.reach_vox)) {
    return Error("the sheet is " + std::to_string(static_cast<int>(std::lround(hit.distance))) +
                 " voxels from the tool; move within " +
                 std::to_string(static_cast<int>(options.reach_vox)) + " to grab it");
  }
  nurbs::NurbsSurface start = *surface_;
  std::vector<double> f;
  if (options.influence == SheetInfluence::kZone) {
    nurbs::ParameterZone zone;
    zone.centre = {hit.u, hit.v};
    // The radius is relative to the domain; a zone spilling over the
    // domain's border is clipped by it (no control point lies outside).
    zone.radius =
        std::clamp(options.radius, 1e-3, 10.0) *
        std::max(surface_->u_max() - surface_->u_min(), surface_->v_max() - surface_->v_min());
    auto refined = nurbs::refine_in_zone(start, hit.u, hit.v, zone, kZoneMinPoints, 4096);
    if (!refined.ok()) return refined.error();
    start = std::move(refined.value());
    auto zf = nurbs::zone_influence(start, hit.u, hit.v, zone);
    if (!zf.ok()) return zf.error();
    f = std::move(zf.value());
  } else {
    f = influence_for(start, hit.u, hit.v, options);
  }
  auto live = nurbs::PathDeformation::live(start, hit.u, hit.v, f, kExpectedLiveSteps);
  if (!live.ok()) return live.error();
  drag_.emplace(Drag{*surface_,
                     f,
                     start,
                     hit.u,
                     hit.v,
                     tip,
                     {hit.point},
                     hit.point,
                     std::move(live.value()),
                     options});
  surface_ = drag_->live.surface();
  retessellate();  // refinement changed the knots
  return {};
}

void SheetEditor::drag(glm::dvec3 tip) {
  if (!drag_) return;
  // The grabbed point keeps its offset from the tip.
  const glm::dvec3 target = drag_->path.front() + (tip - drag_->tip_at_grab);
  if (!(glm::length(target - drag_->path.back()) < 1e6)) return;  // not finite, or absurd
  drag_->latest = target;
  if (!(glm::length(target - drag_->path.back()) >= drag_->options.path_step_vox)) return;
  drag_->path.push_back(target);
  const std::optional<nurbs::PathStep> step = drag_->live.push_point(target);
  if (!step) return;
  surface_ = drag_->live.surface();
  tessellator_->update(*surface_, step->moved, step->motion ? &*step->motion : nullptr);
  ++version_;
}

void SheetEditor::release() {
  if (!drag_) return;
  Drag d = std::move(*drag_);
  drag_.reset();
  if (d.latest != d.path.back()) {  // the tip's last move, shorter than a step
    d.path.push_back(d.latest);
    d.live.push_point(d.latest);
  }
  if (d.path.size() < 2) {  // grabbed and let go: nothing changes
    surface_ = std::move(d.before);
    retessellate();
    return;
  }
  // The device's path as a smooth curve: about one control point per four
  // path points (A9.7 keeps both ends exact, so C(0) = S(u, v)).
  std::optional<nurbs::NurbsSurface> result;
  if (d.path.size() >= 4) {
    const int controls = std::clamp(static_cast<int>(d.path.size()) / 4, 4, 32);
    auto curve = nurbs::fit_curve(d.path, 3, controls);
    if (curve.ok()) {
      auto along = nurbs::PathDeformation::from_curve(d.start, d.u, d.v, d.influence, *curve);
      if (along.ok()) {
        along->run();
        last_residual_ = along->residual();
        result = along->surface();
      }
    }
  }
  if (!result) {  // too short to fit: the live steps, finished exactly
    d.live.finish();
    last_residual_ = d.live.residual();
    result = d.live.surface();
  }
  remember(std::move(d.before));
  surface_ = std::move(result);
  retessellate();
}

std::optional<glm::dvec3> SheetEditor::grabbed_target() const {
  if (!drag_) return std::nullopt;
  return drag_->path.back();
}

bool SheetEditor::undo() {
  return step(undo_, redo_);
}

bool SheetEditor::redo() {
  return step(redo_, undo_);
}

bool SheetEditor::step(History& from, History& to) {
  if (drag_) release();
  if (from.empty()) return false;
  to.push_back(std::move(surface_));
  surface_ = std::move(from.back());
  from.pop_back();
  retessellate();
  return true;
}

}  // namespace sculpt::station
