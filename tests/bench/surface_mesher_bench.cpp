// The window's mesher (station/view/surface_mesher.h) where a new volume
// meets the first dabs on it: the case its refiner is for. A project opened
// or a new block is shown coarse at once; a big dab right after it is
// timed from its hand-over to its first mesh published. Without the
// refiner the dab waited for the whole volume's full-detail pass.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <thread>
#include <vector>

#include "sculpt/core/sculpt/sculptor.h"
#include "sculpt/core/shapes/analytic_shapes.h"
#include "sculpt/core/tool/tool.h"
#include "sculpt/station/view/surface_mesher.h"

namespace sculpt::station {
namespace {

using Clock = std::chrono::steady_clock;

struct Shown {
  Clock::time_point first, full_detail;
};

// Takes what the mesher publishes until it holds `change`, and when
// `until_full_detail` until it holds it at full detail.
Shown published(SurfaceMesher& mesher, uint64_t change, bool until_full_detail) {
  Shown shown;
  bool first = false;
  for (;;) {
    if (std::optional<SurfaceDelta> delta = mesher.take()) {
      if (!first && delta->change >= change) {
        first = true;
        shown.first = Clock::now();
        if (!until_full_detail) return shown;
      }
      if (delta->full_detail_change >= change) {
        shown.full_detail = Clock::now();
        return shown;
      }
    }
    std::this_thread::sleep_for(std::chrono::microseconds(50));
  }
}

double ms(Clock::duration d) {
  return std::chrono::duration<double, std::milli>(d).count();
}

void BM_MesherBigDabOnANewVolume(benchmark::State& state) {
  // The demo's head is about this size; its first balls have radius 66.
  const core::Volume sphere = core::sphere_volume(256);
  const core::Tool ball = core::make_sphere_tool(66.0f);
  const std::vector<int> full(static_cast<size_t>(sphere.brick_count()), 0);
  SurfaceMesher mesher(2, 0.0f);
  uint64_t generation = 0;
  double shown_ms = 0, dab_full_detail_ms = 0, full_detail_ms = 0;
  for (auto _ : state) {
    core::Volume volume = sphere;
    core::Sculptor sculptor(volume);
    sculptor.set_tool(ball);
    const Clock::time_point opened = Clock::now();
    const uint64_t first = mesher.submit(volume, ++generation, full);
    shown_ms += ms(published(mesher, first, false).first - opened);
    // A ball half into the sphere's surface, as the demo's head is built.
    core::Dab dab;
    dab.position_vox = glm::vec3(127.5f + 0.35f * 256.0f, 127.5f, 127.5f);
    sculptor.dab(dab);
    const Clock::time_point handed = Clock::now();
    const uint64_t change = mesher.submit(volume, generation, full);
    const Shown dab_shown = published(mesher, change, true);
    state.SetIterationTime(ms(dab_shown.first - handed) * 1e-3);
    dab_full_detail_ms += ms(dab_shown.full_detail - handed);
    mesher.wait_until_meshed();
    full_detail_ms += ms(Clock::now() - opened);
  }
  const auto n = static_cast<double>(state.iterations());
  state.counters["volume_shown_ms"] = shown_ms / n;
  state.counters["dab_full_detail_ms"] = dab_full_detail_ms / n;
  state.counters["all_full_detail_ms"] = full_detail_ms / n;
}
BENCHMARK(BM_MesherBigDabOnANewVolume)
    ->UseManualTime()
    ->Iterations(10)
    ->Unit(benchmark::kMillisecond);

// What the sculpting thread pays to hand a big dab's bricks to the mesher
// (SurfaceMesher::submit): the demo's 66-voxel ball on the 256^3 sphere,
// then the same hand-over for a whole new 512^3 volume (a new block, an
// opened project). submit() is timed, the dab before it is counted
// (dab_ms), the mesher's work is not.
void BM_HandOver(benchmark::State& state) {
  const bool whole = state.range(0) == 1;
  const core::Volume sphere = core::sphere_volume(whole ? 512 : 256);
  const core::Tool ball = core::make_sphere_tool(66.0f);
  const std::vector<int> full(static_cast<size_t>(sphere.brick_count()), 0);
  SurfaceMesher mesher(2, 0.0f);
  uint64_t generation = 1;
  core::Volume volume = sphere;
  mesher.submit(volume, generation, full);
  mesher.wait_until_meshed();
  core::Sculptor sculptor(volume);
  sculptor.set_tool(ball);
  int64_t i = 0;
  double dab_ms = 0;
  for (auto _ : state) {
    if (!whole) {
      const Clock::time_point dabbed = Clock::now();
      core::Dab dab;
      const float a = 0.3f * static_cast<float>(i++);
      dab.position_vox =
          glm::vec3(127.5f) + 0.35f * 256.0f * glm::vec3(std::cos(a), std::sin(a), 0.0f);
      dab.mode = i % 2 ? core::SculptMode::kAdd : core::SculptMode::kSubtract;
      sculptor.dab(dab);
      dab_ms += ms(Clock::now() - dabbed);
    } else {
      ++generation;
    }
    const Clock::time_point start = Clock::now();
    mesher.submit(volume, generation, full);
    state.SetIterationTime(std::chrono::duration<double>(Clock::now() - start).count());
    mesher.wait_until_meshed();
  }
  // The dab itself: it writes bricks the mesher may still hold.
  state.counters["dab_ms"] = dab_ms / static_cast<double>(state.iterations());
}
BENCHMARK(BM_HandOver)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("whole_512")
    ->UseManualTime()
    ->Iterations(12)
    ->Unit(benchmark::kMillisecond);

// The autosave's copy of the volume, made on the sculpting thread before
// another thread writes it: the 256^3 and 512^3 spheres.
void BM_VolumeCopy(benchmark::State& state) {
  const core::Volume sphere = core::sphere_volume(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    core::Volume copy = sphere;
    benchmark::DoNotOptimize(copy);
  }
}
BENCHMARK(BM_VolumeCopy)->Arg(256)->Arg(512)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace sculpt::station
