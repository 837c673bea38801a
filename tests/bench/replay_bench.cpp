// Session replay benchmark (issue: sessions): the bundled demo replayed as
// fast as possible through parsers, normaliser, pose, sampler, sculptor and
// mesh cache. Reports dabs per second and the ratio to the recording's own
// duration (target: at least 20x faster than real time).

#include <benchmark/benchmark.h>

#include "sculpt/sim/session/session_file.h"
#include "sculpt/sim/synth/bundled_sessions.h"
#include "sculpt/station/app/session_replay.h"

namespace sculpt::station {
namespace {

void BM_ReplayDemo(benchmark::State& state) {
  const auto session = sim::read_session_file(sim::bundled_session_path("demo"));
  if (!session.ok()) {
    state.SkipWithError(session.error().message().c_str());
    return;
  }
  const bool mesh = state.range(0) != 0;
  int64_t dabs = 0;
  double session_seconds = 0;
  ReplayOptions options;
  options.fast = true;
  for (auto _ : state) {
    StationLoop::Options o;
    o.mesh = mesh;
    StationLoop loop(o);
    const auto r = replay_session(*session, "demo", loop, options);
    dabs = loop.counters().dabs;
    session_seconds = r->session_seconds;
    benchmark::DoNotOptimize(loop.volume().content_hash());
  }
  state.counters["dabs"] = static_cast<double>(dabs);
  state.counters["dabs_per_s"] =
      benchmark::Counter(static_cast<double>(dabs), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["x_real_time"] =
      benchmark::Counter(session_seconds, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ReplayDemo)
    ->Arg(1)
    ->Arg(0)
    ->ArgName("mesh")
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)
    ->UseRealTime();

}  // namespace
}  // namespace sculpt::station
