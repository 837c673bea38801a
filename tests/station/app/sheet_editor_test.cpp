#include "sculpt/station/app/sheet_editor.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "sculpt/core/nurbs/influence.h"
#include "sculpt/core/nurbs/point_inversion.h"

namespace sculpt::station {
namespace {

namespace nurbs = core::nurbs;

constexpr double kResidual = 1e-9;

SheetEditor sheet_at(glm::dvec3 centre, int axis = 2) {
  SheetEditor e;
  e.set(SheetEditor::flat(centre, 40.0, 8, axis));
  return e;
}

TEST(SheetEditor, PlacesAFlatSheetCentredAndFacingTheAxis) {
  for (int axis = 0; axis < 3; ++axis) {
    const glm::dvec3 centre(30.0, 31.0, 32.0);
    const nurbs::NurbsSurface s = SheetEditor::flat(centre, 40.0, 8, axis);
    const glm::dvec3 mid = nurbs::evaluate(s, 0.5, 0.5);
    EXPECT_NEAR(glm::length(mid - centre), 0.0, 1e-12);
    const glm::dvec3 n = nurbs::normal(s, 0.5, 0.5);
    EXPECT_NEAR(std::abs(n[axis]), 1.0, 1e-12) << "axis " << axis;
    // Corners 40 voxels apart along both in-plane axes.
    const glm::dvec3 d = nurbs::evaluate(s, 1.0, 1.0) - nurbs::evaluate(s, 0.0, 0.0);
    EXPECT_NEAR(d[(axis + 1) % 3], 40.0, 1e-12);
    EXPECT_NEAR(d[(axis + 2) % 3], 40.0, 1e-12);
  }
}

TEST(SheetEditor, RefusesAGrabAwayFromTheSheet) {
  SheetEditor e;
  const Status none = e.grab({0, 0, 0}, {});
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.error().message(), "there is no sheet to grab");
  e = sheet_at({32, 32, 32});
  const Status far = e.grab({32, 32, 50}, {});
  ASSERT_FALSE(far.ok());
  EXPECT_EQ(far.error().message(),
            "the sheet is 18 voxels from the tool; move within 6 to grab it");
  EXPECT_FALSE(e.dragging());
}

TEST(SheetEditor, DraggedPointEndsExactlyWhereTheDeviceTookIt) {
  for (SheetInfluence influence :
       {SheetInfluence::kNatural, SheetInfluence::kGaussian, SheetInfluence::kZone}) {
    SheetEditor e = sheet_at({32, 32, 32});
    const nurbs::NurbsSurface before = e.surface();
    SheetDragOptions o;
    o.influence = influence;
    o.radius = influence == SheetInfluence::kZone ? 0.2 : 1.5;
    // The tip 2 voxels above the sheet, off its middle: the grabbed point is
    // the one under it, and keeps that offset from the tip.
    const glm::dvec3 tip0(36.3, 29.1, 34.0);
    ASSERT_TRUE(e.grab(tip0, o).ok());
    ASSERT_TRUE(e.dragging());
    const uint64_t version = e.version();
    // An arc: up 12 voxels while sliding 6 sideways.
    glm::dvec3 tip = tip0;
    for (int i = 1; i <= 30; ++i) {
      tip = tip0 + glm::dvec3(0.2 * i, 0.0, 12.0 * std::sin(i / 30.0 * 1.5707963));
      e.drag(tip);
    }
    EXPECT_GT(e.version(), version) << "the sheet follows live";
    EXPECT_GT(e.path_points(), 10);
    e.release();
    EXPECT_FALSE(e.dragging());
    const nurbs::SurfacePoint grabbed = nurbs::closest_point(before, tip0);
    const glm::dvec3 goal = grabbed.point + (tip - tip0);
    // S(u,v) of the final sheet is the end of the path (the refined sheet
    // has the same (u,v) parametrisation: knot insertion keeps it).
    EXPECT_LT(glm::length(nurbs::evaluate(e.surface(), grabbed.u, grabbed.v) - goal), kResidual)
        << static_cast<int>(influence);
    EXPECT_LT(e.last_residual(), kResidual);
    // Far corners did not move.
    EXPECT_EQ(nurbs::evaluate(e.surface(), 0.0, 0.0), nurbs::evaluate(before, 0.0, 0.0));
    if (influence == SheetInfluence::kZone) {
      EXPECT_GT(e.surface().point_count(), before.point_count()) << "the zone was refined";
    } else {
      EXPECT_EQ(e.surface().point_count(), before.point_count());
    }
  }
}

TEST(SheetEditor, ControlPointsOutsideTheInfluenceStayBitIdentical) {
  SheetEditor e = sheet_at({32, 32, 32});
  const nurbs::NurbsSurface before = e.surface();
  SheetDragOptions o;
  o.influence = SheetInfluence::kNatural;
  const glm::dvec3 tip0(26.0, 26.0, 33.0);
  ASSERT_TRUE(e.grab(tip0, o).ok());
  const nurbs::SurfacePoint at = nurbs::closest_point(before, tip0);
  const std::vector<double> f = nurbs::natural_influence(before, at.u, at.v);
  for (int i = 1; i <= 12; ++i)
    e.drag(tip0 + glm::dvec3(0, 0, i));
  e.release();
  int unmoved = 0;
  for (size_t k = 0; k < f.size(); ++k) {
    if (f[k] > 0.0) continue;
    EXPECT_EQ(e.surface().points[k], before.points[k]) << k;
    ++unmoved;
  }
  EXPECT_GT(unmoved, 30);
}

TEST(SheetEditor, AShortPathFinishesExactlyAndAGrabWithoutMotionChangesNothing) {
  SheetEditor e = sheet_at({32, 32, 32});
  const nurbs::NurbsSurface before = e.surface();
  const glm::dvec3 tip0(32.0, 32.0, 32.5);
  ASSERT_TRUE(e.grab(tip0, {}).ok());
  e.release();
  EXPECT_EQ(e.surface().points, before.points);
  ASSERT_TRUE(e.grab(tip0, {}).ok());
  e.drag(tip0 + glm::dvec3(0, 0, 3));  // two path points: no curve to fit
  e.release();
  EXPECT_LT(e.last_residual(), kResidual);
  EXPECT_NEAR(nurbs::evaluate(e.surface(), 0.5, 0.5).z, 35.0, 1e-9);
}

TEST(SheetEditor, UndoAndRedoRestoreTheSheetBitForBit) {
  SheetEditor e;
  e.set(SheetEditor::flat({32, 32, 32}, 40.0, 8, 2));
  const nurbs::NurbsSurface placed = e.surface();
  ASSERT_TRUE(e.grab({32, 32, 33}, {}).ok());
  for (int i = 1; i <= 10; ++i)
    e.drag({32.0, 32.0 + i, 33.0 + i});
  e.release();
  const nurbs::NurbsSurface dragged = e.surface();
  ASSERT_NE(dragged.points, placed.points);
  ASSERT_TRUE(e.undo());
  EXPECT_EQ(e.surface().points, placed.points);
  EXPECT_FALSE(e.mesh().positions.empty());
  ASSERT_TRUE(e.undo());  // the placing
  EXPECT_FALSE(e.has_sheet());
  EXPECT_TRUE(e.mesh().positions.empty());
  EXPECT_FALSE(e.undo());
  ASSERT_TRUE(e.redo());
  ASSERT_TRUE(e.redo());
  EXPECT_EQ(e.surface().points, dragged.points);
  EXPECT_EQ(e.surface().knots_u, dragged.knots_u);
  EXPECT_FALSE(e.redo());
}

}  // namespace
}  // namespace sculpt::station
