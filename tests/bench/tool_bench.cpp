// Discrete tool benchmarks (issue 3, "Discrete tools for virtual sculpture"
// §3). Rotation workload: the peers.py tool sphere (sphere_density(m, 0.4))
// rotated by Euler xyz (30, 45, 60) degrees about its centre; compare with
//   /usr/bin/python3 ../shared/bench/peers.py rot
// run in the same session (scipy.ndimage.affine_transform, order 0 and 1).
// Note that scipy fills an m^3 output, while the rotation here fills the
// bounding box of the rotated tool (about 2.5x as many voxels at this angle).
//
// Table 2 of the paper: BM_ToolRotate/m/method/sampling/angles with angles=1
// averaging over 16 fixed random orientations, as the paper averages "various
// rotation angles" (method 0 brute, 1 incremental; sampling 0 nearest, 1
// trilinear).
//
// Dab workload: the 32^3 tool sphere dabbed on the surface of the 256^3
// peers.py sphere (radius 0.35 * 256), alternating add and subtract so the
// material stays a surface, in strokes of 30 dabs; per-dab median and p99
// come from manual timing (thread CPU time).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "sculpt/base/memory_reuse.h"
#include "sculpt/core/sculpt/sculptor.h"
#include "sculpt/core/shapes/analytic_shapes.h"
#include "sculpt/core/tool/tool_rotation.h"
#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

double thread_cpu_us() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e6 + static_cast<double>(t.tv_nsec) * 1e-3;
}

Tool peers_tool(int m) {
  return tool_from_grid(sphere_density(m, 0.4f));
}

// Fixed pseudo-random unit quaternions (a deterministic sequence).
std::vector<glm::quat> orientations(int count, uint32_t seed) {
  std::vector<glm::quat> out;
  uint32_t s = seed;
  auto next = [&] {
    s = s * 1664525u + 1013904223u;
    return static_cast<float>(s >> 8) / static_cast<float>(1 << 24) * 2.0f - 1.0f;
  };
  while (static_cast<int>(out.size()) < count) {
    const glm::quat q(next(), next(), next(), next());
    const float n = glm::length(q);
    if (n > 0.1f && n <= 1.0f) out.push_back(q / n);
  }
  return out;
}

void BM_ToolRotate(benchmark::State& state) {
  const int m = static_cast<int>(state.range(0));
  const auto method = state.range(1) == 0 ? RotationMethod::kBrute : RotationMethod::kIncremental;
  const auto sampling = state.range(2) == 0 ? Sampling::kNearest : Sampling::kTrilinear;
  const bool many_angles = state.range(3) != 0;
  const PreparedTool tool(peers_tool(m));
  std::vector<glm::mat3> rotations;
  if (many_angles) {
    for (const glm::quat& q : orientations(16, 12345))
      rotations.push_back(glm::mat3_cast(q));
  } else {
    rotations.push_back(euler_xyz_deg({30, 45, 60}));
  }
  size_t i = 0;
  int64_t voxels = 0;
  for (auto _ : state) {
    const RotatedTool r = rotate_tool_about_pivot(tool, rotations[i], method, sampling);
    voxels += static_cast<int64_t>(r.density.size());
    benchmark::DoNotOptimize(r.density.data());
    i = (i + 1) % rotations.size();
  }
  state.counters["out_voxels"] =
      static_cast<double>(voxels) / static_cast<double>(state.iterations());
  state.SetItemsProcessed(voxels);
}
BENCHMARK(BM_ToolRotate)
    ->ArgNames({"m", "method", "aa", "angles"})
    ->ArgsProduct({{16, 32, 64}, {0, 1}, {0, 1}, {0}})
    ->ArgsProduct({{8, 16, 32, 64}, {0, 1}, {0, 1}, {1}})
    ->Unit(benchmark::kMicrosecond);

// Reproductions of the paper's §3.1-3.2 beyond BM_ToolRotate's sphere
// (issue 23), all in its worst case: the whole tool rotated, nothing cached.
//
// method: 0 brute force (a fixed-point matrix product, a bounds test and a
// plain sample per voxel of the rotated box); 1 optimised, as the sculptor
// rotates (Algorithm 1, reach clipping and core fill, AVX2 kernels when the
// CPU has them); 2 Algorithm 1 alone (RotationClipping::kNone: every voxel of
// the box sampled by incremental steps, lines cut to the tool's grid, AVX2
// kernels); 3 as 2 on the scalar kernel (nearest is then the paper's loop;
// trilinear still reads an equal-cornered cell with one load).
// aa: 0 nearest, 1 trilinear (the paper's antialiasing).
//
// Graphs 1-2 (time against angle, 16^3 tool): BM_ToolRotateAngle. The paper
// names neither the axis nor the shape, so two of each: about z (the rotated
// box grows in x and y only, to sqrt 2 at 45 degrees) and about the diagonal
// (1, 1, 1) (it grows in all three); the peers.py sphere and the cube.
//   build/bin/sculpt_bench --benchmark_filter=BM_ToolRotateAngle
//
// Table 2 per shape: BM_ToolRotateShape, the average over the 16 orientations
// of BM_ToolRotate's angles:1 cases, for tools whose grid's largest side is m.
//   build/bin/sculpt_bench --benchmark_filter=BM_ToolRotateShape

enum class Shape { kSphere, kCube, kCylinder, kRing };

// A tool of the shape whose grid's largest side is m voxels (the built-in
// tools' grids are the shape plus its 2-voxel ramp and one voxel: m - 3
// across). The sphere is BM_ToolRotate's (peers.py's sphere_density).
Tool shape_tool(Shape shape, int m) {
  const float across = static_cast<float>(m - 3);
  switch (shape) {
    case Shape::kSphere:
      return peers_tool(m);
    case Shape::kCube:
      return make_cube_tool(across);
    case Shape::kCylinder:
      return make_cylinder_tool(across / 2.0f, across);
    case Shape::kRing:
      return make_ring_tool(across / 3.0f, across / 6.0f);
  }
  return {};
}

// Rotates `tool` by each of `rotations` in turn with the method and the
// sampling in the benchmark's last two arguments.
void run_rotations(benchmark::State& state, const PreparedTool& tool,
                   const std::vector<glm::mat3>& rotations, int method_arg) {
  const int method = static_cast<int>(state.range(method_arg));
  const Sampling sampling =
      state.range(method_arg + 1) != 0 ? Sampling::kTrilinear : Sampling::kNearest;
  const RotationMethod how = method == 0 ? RotationMethod::kBrute : RotationMethod::kIncremental;
  const RotationClipping clipping =
      method >= 2 ? RotationClipping::kNone : RotationClipping::kReachAndCore;
  (void)use_vector_kernel(method != 3);
  size_t i = 0;
  int64_t voxels = 0;
  for (auto _ : state) {
    const RotatedTool r = rotate_tool_about_pivot(tool, rotations[i], how, sampling, clipping);
    voxels += static_cast<int64_t>(r.density.size());
    benchmark::DoNotOptimize(r.density.data());
    i = (i + 1) % rotations.size();
  }
  (void)use_vector_kernel(true);
  state.counters["out_voxels"] =
      static_cast<double>(voxels) / static_cast<double>(state.iterations());
  state.SetItemsProcessed(voxels);
}

// range: shape (0 sphere, 1 cube), axis (0 z, 1 diagonal), degrees, method, aa.
void BM_ToolRotateAngle(benchmark::State& state) {
  const PreparedTool tool(shape_tool(static_cast<Shape>(state.range(0)), 16));
  const glm::vec3 axis = state.range(1) == 0 ? glm::vec3(0, 0, 1) : glm::normalize(glm::vec3(1));
  const float degrees = static_cast<float>(state.range(2));
  glm::mat3 r(glm::rotate(glm::mat4(1.0f), glm::radians(degrees), axis));
  // Float noise (cos 90 deg = -4e-8) to 0, so 0 and 90 about z are exact
  // quarter turns, as euler_xyz_deg() makes them.
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k)
      if (std::abs(r[c][k]) < 1e-6f) r[c][k] = 0.0f;
  run_rotations(state, tool, {r}, 3);
}
BENCHMARK(BM_ToolRotateAngle)
    ->ArgNames({"shape", "axis", "deg", "method", "aa"})
    ->ArgsProduct({{0, 1}, {0, 1}, benchmark::CreateDenseRange(0, 90, 10), {0, 1, 2, 3}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

// range: shape (0 sphere, 1 cube, 2 cylinder, 3 ring), m, method, aa.
void BM_ToolRotateShape(benchmark::State& state) {
  const PreparedTool tool(
      shape_tool(static_cast<Shape>(state.range(0)), static_cast<int>(state.range(1))));
  std::vector<glm::mat3> rotations;
  for (const glm::quat& q : orientations(16, 12345))
    rotations.push_back(glm::mat3_cast(q));
  run_rotations(state, tool, rotations, 2);
}
BENCHMARK(BM_ToolRotateShape)
    ->ArgNames({"shape", "m", "method", "aa"})
    ->ArgsProduct({{0, 1, 2, 3}, {8, 16, 32, 64}, {0, 1, 2, 3}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

// One-off preparation of a reference tool (padding and the uniform-cell
// table, which is built on first use: asked for here).
void BM_ToolPrepare(benchmark::State& state) {
  const Tool t = peers_tool(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    PreparedTool p(t);
    benchmark::DoNotOptimize(p.cells());
  }
}
BENCHMARK(BM_ToolPrepare)->Arg(16)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMicrosecond);

// A sculptor's change to a ball of range(0) voxels (the demo's head 66, the
// bust's 110): the tool made, then set (prepared), on the sculpting thread
// while the next dab waits. Wall time; the counters split it. Freed memory
// kept mapped, as in the window: the tools' tens of megabytes are otherwise
// fresh pages each time.
void BM_BallToolChange(benchmark::State& state) {
  keep_freed_memory(size_t{256} << 20);  // as the window does (memory_reuse.h)
  const auto radius = static_cast<float>(state.range(0));
  Volume v(glm::ivec3(64), 0);
  Sculptor sculptor(v);
  double make_s = 0.0, set_s = 0.0;
  int64_t n = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    Tool tool = make_sphere_tool(radius);
    const auto t1 = std::chrono::steady_clock::now();
    sculptor.set_tool(std::move(tool));
    const auto t2 = std::chrono::steady_clock::now();
    make_s += std::chrono::duration<double>(t1 - t0).count();
    set_s += std::chrono::duration<double>(t2 - t1).count();
    ++n;
  }
  state.counters["make_ms"] = 1e3 * make_s / static_cast<double>(n);
  state.counters["set_ms"] = 1e3 * set_s / static_cast<double>(n);
}
BENCHMARK(BM_BallToolChange)->Arg(66)->Arg(110)->Iterations(10)->Unit(benchmark::kMillisecond);

// Full dabs of the 32^3 tool into the 256^3 sphere. range(0): 0 = a new
// orientation every dab (every contact voxel rotated), 1 = the same
// orientation moved by whole voxels, 2 = the same orientation moved by
// sub-voxel steps (snapped to 1/16 voxel by the cache). range(1): 1 =
// trilinear sampling (the sculptor's default), 0 = nearest, for what
// antialiasing costs a whole dab.
void BM_ToolDab(benchmark::State& state) {
  const int kind = static_cast<int>(state.range(0));
  const Sampling sampling = state.range(1) != 0 ? Sampling::kTrilinear : Sampling::kNearest;
  // Built once for the three runs (a 256^3 volume takes a while), never freed.
  static Volume* material = nullptr;
  if (material == nullptr) material = new Volume(sphere_volume(256, 0.35f));
  Volume v = *material;
  Sculptor sculptor(v);
  sculptor.set_sampling(sampling);
  sculptor.set_tool(peers_tool(32));
  const glm::vec3 centre(127.5f);
  const float radius = 0.35f * 256.0f;
  const std::vector<glm::quat> turns = orientations(4096, 777);
  const glm::quat fixed = glm::quat_cast(euler_xyz_deg({30, 45, 60}));
  std::vector<double> times_us, wall_us, split[3];
  DabStats total;
  int64_t i = 0;
  for (auto _ : state) {
    // Walk a circle on the surface, a dab every ~3 voxels.
    const float a = 0.035f * static_cast<float>(i % 180);
    glm::vec3 p = centre + radius * glm::vec3(std::cos(a), std::sin(a), 0.0f);
    if (kind == 1) p = glm::round(p);
    Dab d{p, kind == 0 ? turns[i % turns.size()] : fixed,
          i % 2 ? SculptMode::kSubtract : SculptMode::kAdd, 1.0f};
    // Strokes of 30 dabs (about 90 voxels of path): undo recording, a copy
    // of each brick the first time a stroke changes it, is part of the cost.
    if (i % 30 == 0) {
      sculptor.end_stroke();
      sculptor.begin_stroke();
    }
    // The
    // percentiles use the thread's CPU time: on a shared machine wall time
    // also counts other processes' turns.
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = thread_cpu_us();
    const DabStats one = sculptor.dab(d);
    total += one;
    split[0].push_back(static_cast<double>(one.decode_ns) * 1e-3);
    split[1].push_back(static_cast<double>(one.apply_ns) * 1e-3);
    split[2].push_back(static_cast<double>(one.encode_ns) * 1e-3);
    times_us.push_back(thread_cpu_us() - c0);
    const double us =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    wall_us.push_back(us);
    state.SetIterationTime(us * 1e-6);
    ++i;
  }
  std::sort(times_us.begin(), times_us.end());
  std::sort(wall_us.begin(), wall_us.end());
  const auto pct = [&](double q) {
    return times_us[std::min(times_us.size() - 1,
                             static_cast<size_t>(q * static_cast<double>(times_us.size())))];
  };
  const double n = static_cast<double>(state.iterations());
  state.counters["median_us"] = pct(0.5);
  state.counters["p99_us"] = pct(0.99);
  state.counters["wall_median_us"] = wall_us[wall_us.size() / 2];
  state.counters["bricks_changed"] = total.bricks_changed / n;
  state.counters["bricks_decoded"] = total.bricks_decoded / n;
  // Medians of each part (steady clock, per dab): robust to other processes.
  for (auto& part : split)
    std::sort(part.begin(), part.end());
  state.counters["decode_us"] = split[0][split[0].size() / 2];
  state.counters["rotate_apply_us"] = split[1][split[1].size() / 2];
  state.counters["encode_us"] = split[2][split[2].size() / 2];
  state.counters["voxel_hit_rate"] = sculptor.cache().stats().voxel_hit_rate();
  state.counters["rotated_per_dab"] =
      static_cast<double>(sculptor.cache().stats().voxels_rotated) / n;
}
BENCHMARK(BM_ToolDab)
    ->ArgsProduct({{0, 1, 2}, {1, 0}})
    ->ArgNames({"case", "aa"})
    ->Iterations(2000)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

// The demo's head ball (radius 66, a 136^3 tool) dabbed on the 256^3
// sphere at a new orientation each time, on range(0) threads: the dab's
// bricks (about a hundred) are decoded and combined on every core
// (Sculptor::apply), so wall time falls with the cores on an idle machine.
void BM_ToolDabBigBall(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  static Volume* material = nullptr;
  if (material == nullptr) material = new Volume(sphere_volume(256, 0.35f));
  Volume v = *material;
  Sculptor sculptor(v);
  sculptor.set_tool(make_sphere_tool(66.0f));
  set_default_threads(threads);
  const glm::vec3 centre(127.5f);
  const float radius = 0.35f * 256.0f;
  const std::vector<glm::quat> turns = orientations(64, 4242);
  int64_t i = 0, bricks = 0, store_ns = 0;
  for (auto _ : state) {
    const float a = 0.3f * static_cast<float>(i);
    const glm::vec3 p = centre + radius * glm::vec3(std::cos(a), std::sin(a), 0.0f);
    const Dab d{p, turns[static_cast<size_t>(i) % turns.size()],
                i % 2 ? SculptMode::kSubtract : SculptMode::kAdd, 1.0f};
    const auto t0 = std::chrono::steady_clock::now();
    const DabStats stats = sculptor.dab(d);
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    bricks += stats.bricks_changed;
    store_ns += stats.encode_ns;  // wall time of the stores (Volume::store_bricks)
    ++i;
  }
  set_default_threads(0);
  state.counters["bricks_changed"] = static_cast<double>(bricks) / static_cast<double>(i);
  state.counters["store_ms"] = static_cast<double>(store_ns) * 1e-6 / static_cast<double>(i);
}
BENCHMARK(BM_ToolDabBigBall)
    ->Arg(1)
    ->Arg(2)
    ->ArgName("threads")
    ->Iterations(30)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sculpt::core
