// The window's mesher (station/view/surface_mesher.h) where a new volume
// meets the first dabs on it: the case its refiner is for. A project opened
// or a new block is shown coarse at once; a big dab right after it is
// timed from its hand-over to its first mesh published. Without the
// refiner the dab waited for the whole volume's full-detail pass.
#include <benchmark/benchmark.h>

#include <chrono>
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

}  // namespace
}  // namespace sculpt::station
