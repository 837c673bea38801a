// Swept strokes against the dabs they replace (issue 21): a stroke of 100
// samples with the 32^3 tool (the peers.py ball, radius 0.4 * 32 = 12.8)
// along a circle on the surface of the 256^3 peers.py sphere (radius
// 0.35 * 256), against 100 dabs at the same samples in one undo stroke.
// Iterations alternate subtract and add so the material stays a surface.
//
// range(0): 0 = 100 dabs, 1 = one swept stroke through the 100 samples
// given at once (sweep_stroke(): a stamp's path, or a fast move's dabs in
// the station), 2 = the same stroke given a sample at a time (a slow move in
// the station: each segment's bricks combined and stored on their own).
// range(1): 0 = the ball made by make_sphere_tool() (swept exactly, as a
// capsule), 1 = the same ball as a plain grid (tool_from_grid(), swept by
// placements along each segment: what a tool file or a sculpture costs).
// range(2): sample spacing in voxels (3: BM_ToolDab's; 8: the station's
// default, a quarter of the tool's size).
// One thread (set_default_threads(1)), timed by the thread's CPU time, so
// other processes on a shared machine do not count.

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <functional>
#include <memory>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "sculpt/base/memory_reuse.h"
#include "sculpt/core/sculpt/stroke.h"
#include "sculpt/core/shapes/analytic_shapes.h"
#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

// The peers.py 256^3 sphere (radius 0.35 * 256), to sculpt as the window's
// sculpting thread does.
Volume sphere_to_sculpt() {
  // Freed memory kept (memory_reuse.h): an undo step's brick copies reuse
  // the pages the steps it pushed out freed, instead of faulting in fresh
  // ones at ~8 us a page (measured at spacing 8: the dabs 8.9 -> 7.2 ms,
  // the stroke 22.9 -> 15.6 ms).
  keep_freed_memory(size_t{256} << 20);
  // And 96 MiB of heap touched once (station_window.cpp): without it the
  // first variant a process runs pays its undo copies' first faults (the
  // dabs at spacing 8 measured 8.1 ms first, 6.5 ms after others).
  static const bool warmed = (warm_this_threads_heap(size_t{96} << 20), true);
  (void)warmed;
  static const Volume* material = new Volume(sphere_volume(256, 0.35f));
  return *material;
}

// Where the time went, per iteration, from the sculptor's own timers (wall
// time of each phase; encode_ms includes storing).
void count_where_the_time_went(benchmark::State& state, const DabStats& total, int64_t iterations) {
  const double per = 1e-6 / static_cast<double>(iterations);
  state.counters["decode_ms"] = static_cast<double>(total.decode_ns) * per;
  state.counters["apply_ms"] = static_cast<double>(total.apply_ns) * per;
  state.counters["encode_ms"] = static_cast<double>(total.encode_ns) * per;
  state.counters["bricks_changed"] =
      static_cast<double>(total.bricks_changed) / static_cast<double>(iterations);
  state.counters["voxels_changed"] =
      static_cast<double>(total.voxels_changed) / static_cast<double>(iterations);
}

void BM_StrokeVsDabs(benchmark::State& state) {
  const int64_t sweep = state.range(0);
  const bool grid_tool = state.range(1) != 0;
  const float spacing = static_cast<float>(state.range(2));
  Volume v = sphere_to_sculpt();
  Sculptor sculptor(v);
  sculptor.set_tool(grid_tool ? tool_from_grid(sphere_density(32, 0.4f))
                              : make_sphere_tool(0.4f * 32.0f));
  set_default_threads(1);
  const glm::vec3 centre(127.5f);
  const float radius = 0.35f * 256.0f;
  constexpr int kSamples = 100;
  // One stroke (or its 100 dabs) on the i-th arc: a quarter turn on each
  // time, alternately cut and filled.
  auto run = [&](int64_t i) {
    std::vector<StrokeSample> path;
    const float start = 1.3f * static_cast<float>(i % 4);
    for (int k = 0; k < kSamples; ++k) {
      const float a = start + spacing * static_cast<float>(k) / radius;
      path.push_back({centre + radius * glm::vec3(std::cos(a), std::sin(a), 0.0f),
                      glm::quat(1.0f, 0.0f, 0.0f, 0.0f)});
    }
    const SculptMode mode = i % 2 ? SculptMode::kAdd : SculptMode::kSubtract;
    if (sweep == 1) return sweep_stroke(sculptor, path, {mode, 1.0f, false});
    if (sweep == 2) {
      DabStats stats;
      SweptStroke stroke(sculptor, {mode, 1.0f, false});
      for (const StrokeSample& s : path)
        stats += stroke.add(s);
      return stats;
    }
    DabStats stats;
    sculptor.begin_stroke();
    for (const StrokeSample& s : path)
      stats += sculptor.dab({s.position_vox, s.orientation, mode, 1.0f});
    sculptor.end_stroke();
    return stats;
  };
  // Untimed, a cut and a fill first: the first strokes of a process take
  // fresh memory from the kernel (page faults), which would count against
  // whichever variant runs first.
  for (int64_t w = 0; w < 4; ++w)
    (void)run(w);
  DabStats total;
  int64_t i = 0;
  for (auto _ : state) {
    const double t0 = thread_cpu_s();
    total += run(i);
    state.SetIterationTime(thread_cpu_s() - t0);
    ++i;
  }
  set_default_threads(0);
  // Steady clock: counts other processes' turns too, unlike the CPU time above.
  count_where_the_time_went(state, total, i);
}
BENCHMARK(BM_StrokeVsDabs)
    ->ArgsProduct({{0, 1, 2}, {0, 1}, {3, 8}})
    ->ArgNames({"sweep", "grid_tool", "spacing"})
    ->Iterations(20)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// Presses press(0), press(1), ... untimed twice (the first presses fault in
// their buffers), then once per iteration, timed by the wall clock (a
// sculptor waits for all of a press, whichever threads did it); puts where
// the time went in the counters and sets the default threads back. Returns
// how many presses were made.
int64_t time_presses(benchmark::State& state, const std::function<DabStats(int64_t)>& press) {
  (void)press(0);
  (void)press(1);
  DabStats total;
  int64_t i = 2;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    total += press(i);
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    ++i;
  }
  set_default_threads(0);
  count_where_the_time_went(state, total, i - 2);
  return i;
}

// The registration the presses below share: on one thread and on two
// (range(0)), each timed by the wall clock, in milliseconds.
void on_one_and_two_threads(benchmark::internal::Benchmark* b) {
  b->Arg(1)->Arg(2)->ArgName("threads")->UseManualTime()->Unit(benchmark::kMillisecond);
}

// A ball of radius `ball` pressed once, as the station sculpts it (a
// stroke of one sample), at a new place on the surface of `material` (the
// peers.py sphere, radius 0.35 of its edge) each time, alternately filled
// and cut, on range(0) threads: the bricks are decoded, swept and
// re-encoded on every core. Wall time of the press (a sculptor waits for
// all of it); the counters say where it went (wall time of the decodes,
// the sweep and the stores).
// `hand_over`: the sculptor also copies what it stored for a mesher
// (SculptorOptions::hand_over_voxels), taken after each press as the
// station does.
void time_ball_presses(benchmark::State& state, Volume material, float ball,
                       bool hand_over = false) {
  Sculptor sculptor(material, SculptorOptions{.hand_over_voxels = hand_over});
  sculptor.set_tool(make_sphere_tool(ball));
  set_default_threads(static_cast<int>(state.range(0)));
  const glm::vec3 centre(0.5f * static_cast<float>(material.dims().x - 1));
  const float radius = 0.35f * static_cast<float>(material.dims().x);
  auto press = [&](int64_t i) {
    const float a = 0.7f * static_cast<float>(i);
    const StrokeSample at{centre + radius * glm::vec3(std::cos(a), std::sin(a), 0.0f),
                          glm::quat(1.0f, 0.0f, 0.0f, 0.0f)};
    const DabStats stats =
        sweep_stroke(sculptor, std::span(&at, 1),
                     {i % 2 ? SculptMode::kSubtract : SculptMode::kAdd, 1.0f, false});
    (void)sculptor.take_stored_voxels();
    return stats;
  };
  time_presses(state, press);
}

// The demo's head ball (radius 66: about a hundred bricks) on the 256^3
// sphere.
void BM_StrokeBigBall(benchmark::State& state) {
  time_ball_presses(state, sphere_to_sculpt(), 66.0f);
}
BENCHMARK(BM_StrokeBigBall)->Apply(on_one_and_two_threads)->Iterations(30);

// The same, the sculptor copying each brick it stores for the mesher (the
// window's sculptor does): what that costs the press.
void BM_StrokeBigBallHandingOver(benchmark::State& state) {
  time_ball_presses(state, sphere_to_sculpt(), 66.0f, /*hand_over=*/true);
}
BENCHMARK(BM_StrokeBigBallHandingOver)->Apply(on_one_and_two_threads)->Iterations(30);

// The demo's first ball: the same press on the empty new 256^3 block the
// session starts with, where the tool stands (128, 116, 118). Every brick it
// reaches is uniform, so none is decoded from a pyramid, and each it changes
// is encoded whole. A new block and sculptor each iteration (untimed).
void BM_StrokeBigBallOnANewBlock(benchmark::State& state) {
  (void)sphere_to_sculpt();  // the heap warmed as the station's
  set_default_threads(static_cast<int>(state.range(0)));
  const Tool ball = make_sphere_tool(66.0f);
  const StrokeSample at{glm::vec3(128.0f, 116.0f, 118.0f), glm::quat(1.0f, 0.0f, 0.0f, 0.0f)};
  DabStats total;
  int64_t presses = 0;
  for (auto _ : state) {
    Volume v(glm::ivec3(256), 0);
    Sculptor sculptor(v);
    sculptor.set_tool(ball);
    const auto t0 = std::chrono::steady_clock::now();
    total += sweep_stroke(sculptor, std::span(&at, 1), {SculptMode::kAdd, 1.0f, false});
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    ++presses;
  }
  set_default_threads(0);
  count_where_the_time_went(state, total, presses);
}
BENCHMARK(BM_StrokeBigBallOnANewBlock)->Apply(on_one_and_two_threads)->Iterations(20);

// The demo's head stroke after its first press: the same ball moved a
// spacing each segment (13.2 voxels: the demo's 0.1 of the tool's size, its
// diameter) up +y, as a sculptor's slow move gives the station a sample at
// a time, the sculptor handing what it stores to a mesher (the window's).
// Timed: one segment. A new block and stroke every three segments (outside
// the manual time), as the demo's stroke of 36 voxels has.
void BM_StrokeBigBallSegment(benchmark::State& state) {
  (void)sphere_to_sculpt();  // the heap warmed as the station's
  set_default_threads(static_cast<int>(state.range(0)));
  constexpr int kSegments = 3;
  constexpr float kRadiusVox = 66.0f;
  constexpr float kSpacingVox = 0.1f * 2.0f * kRadiusVox;
  std::unique_ptr<Volume> v;
  std::unique_ptr<Sculptor> sculptor;
  std::unique_ptr<SweptStroke> stroke;
  glm::vec3 at(128.0f, 116.0f, 118.0f);
  int segment = kSegments;
  DabStats total;
  int64_t timed = 0;
  for (auto _ : state) {
    if (segment == kSegments) {
      stroke.reset();
      sculptor.reset();
      v = std::make_unique<Volume>(glm::ivec3(256), 0);
      sculptor = std::make_unique<Sculptor>(*v, SculptorOptions{.hand_over_voxels = true});
      sculptor->set_tool(make_sphere_tool(kRadiusVox));
      stroke =
          std::make_unique<SweptStroke>(*sculptor, StrokeOptions{SculptMode::kAdd, 1.0f, false});
      at = glm::vec3(128.0f, 116.0f, 118.0f);
      (void)stroke->add(StrokeSample{at, glm::quat(1.0f, 0.0f, 0.0f, 0.0f)});
      (void)sculptor->take_stored_voxels();
      segment = 0;
    }
    at.y += kSpacingVox;
    const auto t0 = std::chrono::steady_clock::now();
    total += stroke->add(StrokeSample{at, glm::quat(1.0f, 0.0f, 0.0f, 0.0f)});
    (void)sculptor->take_stored_voxels();
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    ++segment;
    ++timed;
  }
  stroke.reset();
  set_default_threads(0);
  count_where_the_time_went(state, total, timed);
}
BENCHMARK(BM_StrokeBigBallSegment)->Apply(on_one_and_two_threads)->Iterations(64);

// The bust's biggest ball (radius 110, the tool its session changes to at
// 2.4 s) on the 512^3 sphere: the floor under that dab's first mesh, which
// cannot be made before the dab is sculpted.
void BM_StrokeBustBall(benchmark::State& state) {
  static const Volume* material = new Volume(sphere_volume(512, 0.35f));
  (void)sphere_to_sculpt();  // the heap warmed as the station's
  time_ball_presses(state, *material, 110.0f);
}
BENCHMARK(BM_StrokeBustBall)->Apply(on_one_and_two_threads)->Iterations(10);

// The demo's ring (major radius 12, minor 5) turning as a 6-DOF device
// turns it, mirrored as the demo's nose is: each iteration a press of two
// samples 8.4 voxels apart (the demo's longest ring segment) at a new place
// on the 256^3 sphere and a new orientation, so each of the segment's 17
// placements, and their mirror images, is rotated anew, on range(0)
// threads. Wall time of the press; the counters say where it went.
void BM_StrokeTurningRing(benchmark::State& state) {
  Volume v = sphere_to_sculpt();
  Sculptor sculptor(v);
  sculptor.set_tool(make_ring_tool(12.0f, 5.0f));
  sculptor.set_mirror(MirrorPlane{0, 128.0f});
  set_default_threads(static_cast<int>(state.range(0)));
  const glm::vec3 centre(127.5f);
  const float radius = 0.35f * 256.0f;
  const glm::vec3 axis = glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f));
  auto press = [&](int64_t i) {
    const float a = 0.37f * static_cast<float>(i);
    const glm::vec3 on = centre + radius * glm::vec3(0.3f * std::cos(a), 0.3f * std::sin(a), 0.9f);
    const glm::quat turn = glm::angleAxis(0.05f * static_cast<float>(i), axis);
    const StrokeSample path[2] = {{on, turn},
                                  {on + glm::vec3(0.0f, 8.4f, 0.0f),
                                   glm::angleAxis(0.05f * static_cast<float>(i) + 0.003f, axis)}};
    return sweep_stroke(sculptor, path,
                        {i % 2 ? SculptMode::kSubtract : SculptMode::kAdd, 1.0f, false});
  };
  const int64_t presses = time_presses(state, press);
  state.counters["voxels_rotated"] =
      static_cast<double>(sculptor.rotation_cache_stats().voxels_rotated) /
      static_cast<double>(presses);
}
BENCHMARK(BM_StrokeTurningRing)->Apply(on_one_and_two_threads)->Iterations(40);

}  // namespace
}  // namespace sculpt::core
