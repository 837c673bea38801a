// The haptic loop as a force device runs it (DESIGN.md §5a): the simulated
// arm pressing on and sliding over a clay slab, the station's contact law on
// the patch the sculpting side keeps, the safety rules.
//   BM_HapticLoopTick     one tick's cost in virtual time (p50/p99, us)
//   BM_HapticLoopRealTime 3 s of the loop on its real-time thread, the
//                         sculpting side polling beside it: late ticks
//                         (period > 1.5 ms) and period percentiles
// The same figures with the window sculpting the demo: `sculpt run --device
// sim:sim/sessions/demo.scs --haptic sim-arm:sim/sessions/explore.hand
// --until-replayed --stats S.json` (its "haptics" section).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <thread>
#include <vector>

#include "sculpt/core/haptics/patch_keeper.h"
#include "sculpt/hal/force/sim_arm.h"
#include "sculpt/hal/haptics/haptic_loop.h"
#include "sculpt/hal/haptics/haptic_thread.h"
#include "sculpt/station/app/station_loop.h"
#include "sculpt/station/haptics/contact_force_law.h"

namespace sculpt::station {
namespace {

constexpr float kRadiusVox = 4.0f;

// Circles of 10 mm on the slab's top, pressing 3 mm in, for `seconds`.
hal::HandScript sliding_hand(double seconds) {
  hal::HandScript hand;
  for (double t = 0.0; t <= seconds; t += 0.05) {
    const float a = static_cast<float>(t * 2.0);
    hand.path.push_back({t, glm::vec3(10.0f * std::cos(a), -3.0f, 10.0f * std::sin(a))});
  }
  return hand;
}

struct Rig {
  core::Volume volume = clay_block(glm::ivec3(128), 32);  // top at y = 96
  core::DistancePatchOptions options{
      core::patch_edge_for_reach(0.0f, core::band_for_sphere(kRadiusVox)),
      core::band_for_sphere(kRadiusVox), 1};
  core::PatchExchange exchange{options.edge};
  core::PatchKeeper keeper{exchange, options};
  hal::SimArm arm;
  ContactForceLaw law;
  hal::HapticLoop loop;

  explicit Rig(double seconds)
      : arm(sliding_hand(seconds)),
        law(
            exchange, arm.limits(),
            [] {
              ContactSettings s;
              s.haptic.proxy.radius_vox = kRadiusVox;
              return s;
            }(),
            glm::vec3(64.0f, 96.0f + kRadiusVox + 2.0f, 64.0f)),
        loop(arm, law) {
    keeper.update(volume, 1, glm::vec3(64.0f, 100.0f, 64.0f));
    loop.enable();
  }
  // The sculpting side's share: the newest contact, the patch kept round it.
  void sculpting_side() {
    ContactRecord r, newest;
    bool any = false;
    while (law.contacts().try_pop(r))
      newest = r, any = true;
    hal::HapticTickRecord t;
    while (loop.records().try_pop(t)) {
    }
    if (any) keeper.update(volume, 1, newest.proxy_vox);
  }
};

void BM_HapticLoopTick(benchmark::State& state) {
  Rig rig(3600.0);
  std::vector<double> us;
  us.reserve(1 << 20);
  int64_t t_ns = 0, contacts = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    rig.loop.tick(t_ns);
    us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start)
                     .count());
    t_ns += 1'000'000;
    state.PauseTiming();
    contacts += rig.law.contacts().size_approx() > 0;
    rig.sculpting_side();
    state.ResumeTiming();
  }
  std::sort(us.begin(), us.end());
  state.counters["p50_us"] = us[us.size() / 2];
  state.counters["p99_us"] = us[std::min(us.size() - 1, us.size() * 99 / 100)];
  state.counters["max_force_n"] = rig.loop.live().max_force_n.load();
}
BENCHMARK(BM_HapticLoopTick)->Unit(benchmark::kMicrosecond);

void BM_HapticLoopRealTime(benchmark::State& state) {
  for (auto _ : state) {
    Rig rig(3.0);
    hal::HapticThread thread(rig.loop, rig.arm);
    thread.start();
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(3);
    while (std::chrono::steady_clock::now() < end) {
      rig.sculpting_side();
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    thread.stop();
    const hal::HapticLiveCounters& live = rig.loop.live();
    const double ticks = static_cast<double>(live.ticks.load());
    state.counters["ticks"] = ticks;
    state.counters["late_share"] =
        ticks > 0 ? static_cast<double>(live.late_ticks.load()) / ticks : 0;
    state.counters["period_p50_us"] = rig.loop.periods().quantile_us(0.5);
    state.counters["period_p99_us"] = rig.loop.periods().quantile_us(0.99);
    state.counters["period_max_us"] = rig.loop.periods().max_us();
    state.counters["realtime"] = thread.realtime() ? 1 : 0;
  }
}
BENCHMARK(BM_HapticLoopRealTime)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

}  // namespace
}  // namespace sculpt::station
