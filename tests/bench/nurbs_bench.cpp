// NURBS deformation benchmarks (issue 9): the paper's Figure 14 and 15 cases.
// A 15 x 10 bicubic sheet (core::nurbs::example_sheet), S(0.5, 0.5) dragged
// along an arch-shaped cubic path; Figure 14: a star-shaped zone and 80 steps
// (paper: 240 ms on a PowerPC 1.33 GHz), Figure 15: a circular zone and 100
// steps (paper: 420 ms). One iteration is the whole path: refinement of the
// control net inside the zone until it holds at least N control points, the
// zone influence, the first tessellation, then every step followed by the
// re-tessellation of the patches it touched (what the station redraws).
// There is no peer library for this workload; the paper's figures are the
// reference.

#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

#include "sculpt/core/nurbs/influence.h"
#include "sculpt/core/nurbs/path_deformation.h"
#include "sculpt/core/nurbs/point_inversion.h"
#include "sculpt/core/nurbs/punctual_constraint.h"
#include "sculpt/core/nurbs/surface_tessellator.h"

namespace sculpt::core::nurbs {
namespace {

// Mesh cells per knot span and direction of the unrefined 12 x 7-span sheet.
constexpr int kCellsPerSpan = 4;

ParameterZone figure_zone(bool star) {
  ParameterZone z;
  if (!star) {
    z.centre = {0.5, 0.5};
    z.radius = 0.3;
    return z;
  }
  z.shape = ParameterZone::Shape::kPolygon;
  for (int k = 0; k < 10; ++k) {
    const double a = k * std::numbers::pi / 5.0;
    const double r = k % 2 == 0 ? 0.32 : 0.16;
    z.polygon.emplace_back(0.5 + r * std::cos(a), 0.5 + r * std::sin(a));
  }
  return z;
}

NurbsCurve arch(glm::dvec3 a) {
  NurbsCurve c;
  c.degree = 3;
  c.knots = uniform_clamped_knots(3, 5);
  c.points = {a, a + glm::dvec3(0, 0, 30), a + glm::dvec3(15, 0, 45), a + glm::dvec3(30, 5, 30),
              a + glm::dvec3(35, 10, 10)};
  return c;
}

// range(0): steps N; range(1): 1 = star zone (Figure 14), 0 = circle (Figure 15);
// range(2): mesh density: 0 = 4 cells per span of the original sheet (48 x 28
// cells whatever the refinement: SurfaceTessellator::with_cells, what the
// station draws), 1 = 4 cells per span of the refined sheet (about 4 x more
// vertices inside the zone).
void BM_NurbsPath(benchmark::State& state) {
  const int steps = static_cast<int>(state.range(0));
  const bool star = state.range(1) != 0;
  const bool dense = state.range(2) != 0;
  const NurbsSurface sheet = example_sheet();
  const ParameterZone zone = figure_zone(star);
  const NurbsCurve path = arch(evaluate(sheet, 0.5, 0.5));
  int64_t patches = 0;
  int points = 0;
  int total_patches = 0;
  double residual = 0.0;
  int64_t evaluated = 0, rigid = 0;
  size_t vertices = 0;
  for (auto _ : state) {
    NurbsSurface refined = refine_in_zone(sheet, 0.5, 0.5, zone, steps).value();
    std::vector<double> f = zone_influence(refined, 0.5, 0.5, zone).value();
    PathOptions options;
    options.steps = steps;
    PathDeformation d =
        PathDeformation::from_curve(std::move(refined), 0.5, 0.5, std::move(f), path, options)
            .value();
    SurfaceTessellator mesh =
        dense ? SurfaceTessellator(d.surface(), kCellsPerSpan)
              : SurfaceTessellator::with_cells(d.surface(), 12 * kCellsPerSpan, 7 * kCellsPerSpan);
    patches = 0;
    while (!d.done()) {
      const PathStep s = d.step();
      patches += mesh.update(d.surface(), s.moved, s.motion ? &*s.motion : nullptr);
    }
    benchmark::DoNotOptimize(mesh.mesh().positions.data());
    points = d.surface().point_count();
    evaluated = mesh.vertices_evaluated();
    vertices = mesh.mesh().positions.size();
    rigid = mesh.vertices_moved_rigidly();
    total_patches = mesh.patch_count();
    residual = d.residual();
  }
  state.counters["control_points"] = points;
  state.counters["patches"] = total_patches;
  state.counters["patches_per_step"] = static_cast<double>(patches) / steps;
  state.counters["residual"] = residual;
  state.counters["mesh_vertices"] = static_cast<double>(vertices);
  state.counters["vertices_evaluated"] = static_cast<double>(evaluated);
  state.counters["vertices_rigid"] = static_cast<double>(rigid);
}
BENCHMARK(BM_NurbsPath)
    ->Args({80, 1, 0})
    ->Args({100, 0, 0})
    ->Args({80, 1, 1})
    ->Args({100, 0, 1})
    ->ArgNames({"steps", "star", "dense"})
    ->Unit(benchmark::kMillisecond);

// One linear constraint with natural influence and the patches it re-tessellates.
void BM_NurbsLinearConstraint(benchmark::State& state) {
  NurbsSurface s = example_sheet();
  SurfaceTessellator mesh(s, kCellsPerSpan);
  const glm::dvec3 start = evaluate(s, 0.43, 0.61);
  double z = 0.0;
  for (auto _ : state) {
    z += 0.01;
    const std::vector<double> f = natural_influence(s, 0.43, 0.61);
    const std::vector<int> moved =
        apply_linear_constraint(s, 0.43, 0.61, start + glm::dvec3(0, 0, z), f).value();
    benchmark::DoNotOptimize(mesh.update(s, moved));
  }
}
BENCHMARK(BM_NurbsLinearConstraint)->Unit(benchmark::kMicrosecond);

// Picking: the closest (u, v) to a point near the sheet.
void BM_NurbsPointInversion(benchmark::State& state) {
  const NurbsSurface s = example_sheet();
  const glm::dvec3 query = evaluate(s, 0.37, 0.58) + glm::dvec3(0.5, -0.3, 2.0);
  for (auto _ : state)
    benchmark::DoNotOptimize(closest_point(s, query));
}
BENCHMARK(BM_NurbsPointInversion)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace sculpt::core::nurbs
