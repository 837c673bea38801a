// Haptic contact benchmarks (issue 19): what the 1 kHz tick costs, and what the
// sculpting side spends keeping its patch current. Each reports the median
// and the 99th percentile of single calls (counters p50_us, p99_us), since a
// haptic deadline is missed by the slow call, not the mean.
//   tick:     the sphere proxy (radius 1) and coupling sliding below the
//             surface of a radius-40 ball, one device step of 0.05 voxel a tick
//   tool:     the point shell of a 32^3 tool (a ball of radius 15, 32^3 grid)
//             with its 6-DOF coupling, pressed 2 voxels into the ball's
//             surface and sliding along it
//   refresh:  a 48^3 patch refreshed after a real 32^3 dab (the same ball
//             tool), dab:1 the worst case, the whole ball 6 voxels into the
//             surface, subtracted then added back in turn (a fresh crater or
//             mound every time); dab:2 a stroke, dabs a quarter radius apart
//             sliding across the patch, adding on the way out and carving on
//             the way back; dab:0 the whole 32^3 box marked changed without
//             a change of material
//   recentre: the patch moved by (6, 2, 1) voxels, as the proxy's drift of
//             edge/8 triggers it
//   build:    a 48^3 patch from scratch (first contact, or a jump)

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "sculpt/core/haptics/distance_patch.h"
#include "sculpt/core/haptics/haptic_renderer.h"
#include "sculpt/core/haptics/tool_proxy.h"
#include "sculpt/core/sculpt/sculptor.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::core {
namespace {

const Volume& ball_volume() {
  static const Volume volume = sphere_volume(128, 40.0f / 128.0f);  // radius 40 about 63.5
  return volume;
}

// The median and 99th percentile of the calls timed, as counters.
void report_percentiles(benchmark::State& state, std::vector<double>& us) {
  std::sort(us.begin(), us.end());
  state.counters["p50_us"] = us[us.size() / 2];
  state.counters["p99_us"] = us[std::min(us.size() - 1, us.size() * 99 / 100)];
}

// Times each call of `body`, and reports the median and the 99th percentile.
template <class Body>
void time_calls(benchmark::State& state, Body&& body) {
  std::vector<double> us;
  us.reserve(1 << 16);
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    body();
    us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
                     .count());
  }
  report_percentiles(state, us);
}

void BM_HapticTick(benchmark::State& state) {
  const glm::vec3 centre(63.5f);
  DistancePatch patch;
  HapticRenderer renderer;
  int i = 0;
  double t = 0.0;
  const auto device = [&](int k) {
    const float angle = 0.05f * float(k % 2000) / 38.0f;
    return centre + 38.0f * glm::vec3(std::cos(angle), std::sin(angle), 0.0f);
  };
  patch.build(ball_volume(), device(0));
  // The sculpting side's re-centre runs between ticks, outside the timing.
  std::vector<double> us;
  us.reserve(1 << 20);
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const HapticTick& tick = renderer.tick(patch.snapshot(), device(i++), t += 1e-3);
    benchmark::DoNotOptimize(tick.force_n);
    us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
                     .count());
    if (patch.off_centre(tick.proxy.position_vox)) {
      state.PauseTiming();
      patch.recentre(ball_volume(), tick.proxy.position_vox);
      state.ResumeTiming();
    }
  }
  report_percentiles(state, us);
}
BENCHMARK(BM_HapticTick)->Unit(benchmark::kMicrosecond);

void BM_ToolTick(benchmark::State& state) {
  const glm::vec3 centre(63.5f);
  const Tool tool = make_sphere_tool(15.0f);
  ToolProxy proxy(make_point_shell(tool));
  DistancePatch patch({patch_edge_for_reach(proxy.shell().reach_vox), 4.0f});
  const auto device = [&](int k) {
    const float angle = 0.05f * float(k % 2000) / 53.0f;
    return centre + 53.0f * glm::vec3(std::cos(angle), std::sin(angle), 0.0f);
  };
  const glm::quat level(1, 0, 0, 0);
  patch.build(ball_volume(), device(0));
  proxy.reset(device(0) + glm::vec3(4, 0, 0), level);
  int i = 0;
  std::vector<double> us;
  us.reserve(1 << 20);
  int64_t contacts = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const ToolTick& tick = proxy.update(patch.snapshot(), device(i++), level);
    benchmark::DoNotOptimize(tick.force_n);
    us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
                     .count());
    contacts += tick.points_in_contact;
    if (patch.off_centre(tick.position_vox)) {
      state.PauseTiming();
      patch.recentre(ball_volume(), tick.position_vox);
      state.ResumeTiming();
    }
  }
  report_percentiles(state, us);
  state.counters["shell_points"] = double(proxy.shell().points.size());
  state.counters["points_in_contact"] = double(contacts) / double(us.size());
}
BENCHMARK(BM_ToolTick)->Unit(benchmark::kMicrosecond);

void BM_PatchRefresh(benchmark::State& state) {
  const int kind = static_cast<int>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  Volume volume = sphere_volume(128, 40.0f / 128.0f);
  const glm::vec3 at(63.5f + 40.0f, 63.5f, 63.5f);
  DistancePatch patch({.edge = 48, .band_vox = 4.0f, .threads = threads});
  patch.build(volume, at);
  Sculptor sculptor(volume);
  sculptor.set_tool(make_sphere_tool(15.0f));  // a 32^3 tool grid
  Dab dab;
  dab.position_vox = at + glm::vec3(15.0f - 6.0f, 0.0f, 0.0f);
  const glm::ivec3 lo = glm::ivec3(at) - 16;
  const Box box{lo, lo + 32};
  int step = 0;
  std::vector<double> us;
  int64_t computed = 0;
  for (auto _ : state) {
    state.PauseTiming();
    std::vector<glm::ivec3> bricks;
    if (kind == 1) {
      dab.mode = dab.mode == SculptMode::kSubtract ? SculptMode::kAdd : SculptMode::kSubtract;
    } else if (kind == 2) {
      // Eight dabs of 3.75 voxels out along y, eight back.
      const int k = step++ % 16;
      const float y = k < 8 ? -15.0f + 3.75f * float(k) : 15.0f - 3.75f * float(k - 8);
      dab.position_vox = at + glm::vec3(15.0f - 4.0f, y, 0.0f);
      dab.mode = k < 8 ? SculptMode::kAdd : SculptMode::kSubtract;
    }
    if (kind != 0) {
      (void)sculptor.dab(dab);
      bricks = volume.take_dirty_bricks();
    }
    state.ResumeTiming();
    const auto start = std::chrono::steady_clock::now();
    if (kind != 0) {
      patch.refresh_bricks(volume, bricks);
    } else {
      patch.refresh(volume, box);
    }
    us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
                     .count());
    computed += patch.last_computed_voxels();
  }
  report_percentiles(state, us);
  state.counters["voxels"] = double(computed) / double(us.size());
}
BENCHMARK(BM_PatchRefresh)
    ->Args({1, 1})
    ->Args({2, 1})
    ->Args({0, 1})
    ->Args({1, 2})
    ->ArgNames({"dab", "threads"})
    ->Unit(benchmark::kMicrosecond);

void BM_PatchRecentre(benchmark::State& state) {
  const glm::vec3 a(63.5f + 40.0f, 63.5f, 63.5f);
  const glm::vec3 b = a + glm::vec3(6.0f, 2.0f, 1.0f);
  DistancePatch patch;
  patch.build(ball_volume(), a);
  bool at_a = true;
  time_calls(state, [&] {
    patch.recentre(ball_volume(), at_a ? b : a);
    at_a = !at_a;
  });
  state.counters["voxels"] = double(patch.last_computed_voxels());
}
BENCHMARK(BM_PatchRecentre)->Unit(benchmark::kMicrosecond);

void BM_PatchBuild(benchmark::State& state) {
  const glm::vec3 at(63.5f + 40.0f, 63.5f, 63.5f);
  DistancePatch patch;
  time_calls(state, [&] { patch.build(ball_volume(), at); });
}
BENCHMARK(BM_PatchBuild)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace sculpt::core
