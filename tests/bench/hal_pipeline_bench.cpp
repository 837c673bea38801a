// HAL benchmarks (issue 5): report-to-pose latency through parser,
// normaliser, ring and integrator (median and p99 per report, target well
// under 50 us), and sustained 1 kHz input without drops.
//
// Latencies are measured per report with the monotonic clock and reported as
// counters (median_us, p99_us); the iteration time of Google Benchmark is the
// throughput, not the latency.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <thread>
#include <vector>

#include "sculpt/hal/backends/feed_backend.h"
#include "sculpt/hal/input/device_reader.h"
#include "sculpt/hal/input/spsc_ring.h"
#include "sculpt/hal/parsers/spacemouse_parser.h"
#include "sculpt/hal/pose/pose_integrator.h"
#include "sculpt/hal/types/clock.h"
#include "sculpt/hal/types/quirks.h"

namespace sculpt::hal {
namespace {

// A SpaceMouse Compact combined report: id 1, six int16 axes.
RawEvent compact_report(int64_t t_ns, int i) {
  const auto v = static_cast<int16_t>((i * 37) % 700 - 350);
  uint8_t b[13] = {1};
  for (int a = 0; a < 6; ++a) {
    const auto x = static_cast<int16_t>(a == 0 ? v : v / (a + 1));
    b[1 + 2 * a] = static_cast<uint8_t>(x & 0xFF);
    b[2 + 2 * a] = static_cast<uint8_t>((x >> 8) & 0xFF);
  }
  return RawEvent::report(t_ns, b);
}

// A SpaceMouse Compact plugged into a fake transport, and its open handle.
std::shared_ptr<DeviceFeed> attach_compact(FeedBackend& backend) {
  DeviceInfo info;
  info.path = "bench";
  info.vendor_id = 0x256f;
  info.product_id = 0xc635;
  return backend.attach(info);
}

std::unique_ptr<Device> open_compact(FeedBackend& backend) {
  return std::move(backend.open(backend.enumerate()->front())).value();
}

MotionPipeline compact_pipeline() {
  return MotionPipeline(std::make_unique<SpaceMouseParser>(*find_quirks(0x256f, 0xc635)),
                        NormalizerConfig{});
}

void set_percentiles(benchmark::State& state, std::vector<int64_t>& ns) {
  if (ns.empty()) return;
  std::sort(ns.begin(), ns.end());
  state.counters["median_us"] = static_cast<double>(ns[ns.size() / 2]) * 1e-3;
  state.counters["p99_us"] = static_cast<double>(ns[ns.size() * 99 / 100]) * 1e-3;
  state.counters["max_us"] = static_cast<double>(ns.back()) * 1e-3;
  state.counters["reports"] = static_cast<double>(ns.size());
}

// The work on the path, on one thread: parse, normalise (default config, with
// the one-euro filter), push into the ring, pop, integrate into a pose.
void BM_HalReportToPoseInline(benchmark::State& state) {
  MotionPipeline pipeline = compact_pipeline();
  SpscRing<InputEvent> ring(4096);
  PoseIntegrator integrator;
  std::vector<InputEvent> out;
  std::vector<int64_t> latency;
  latency.reserve(1 << 20);
  int i = 0;
  for (auto _ : state) {
    const int64_t t0 = monotonic_ns();
    const RawEvent raw = compact_report(t0, i++);
    out.clear();
    pipeline.feed(raw, 1, out);
    for (const InputEvent& e : out)
      ring.try_push(e);
    InputEvent e;
    while (ring.try_pop(e))
      integrator.update(e);
    benchmark::DoNotOptimize(integrator.pose());
    if (latency.size() < latency.capacity()) latency.push_back(monotonic_ns() - t0);
  }
  set_percentiles(state, latency);
}
BENCHMARK(BM_HalReportToPoseInline);

// The live path across threads: a report handed to the transport (FeedDevice,
// standing in for the kernel's queue), woken reader thread, parser,
// normaliser, SPSC ring, main loop spinning on poll(), integrator. Latency is
// from the report's arrival stamp to the pose update, one report in flight.
void BM_HalReportToPoseThreaded(benchmark::State& state) {
  FeedBackend backend;
  auto feed = attach_compact(backend);
  DeviceReader reader(1, open_compact(backend), compact_pipeline());
  reader.start();
  PoseIntegrator integrator;
  std::vector<int64_t> latency;
  InputFrame frame;
  int i = 0;
  for (auto _ : state) {
    const int64_t t0 = monotonic_ns();
    feed->push(compact_report(t0, i++));
    const InputEvent* motion = nullptr;
    while (motion == nullptr) {
      frame.clear();
      reader.poll(frame, monotonic_ns());
      for (const InputEvent& e : frame.events) {
        if (e.kind == InputKind::kMotion) motion = &e;
      }
    }
    integrator.update(*motion);
    latency.push_back(monotonic_ns() - motion->t_ns);
  }
  reader.stop();
  set_percentiles(state, latency);
  state.counters["dropped"] = static_cast<double>(reader.counters().dropped);
}
BENCHMARK(BM_HalReportToPoseThreaded)->Iterations(20000)->UseRealTime();

// Sustained 1 kHz for 3 s: reports paced by the clock into the reader, the
// main loop polling at 60 Hz. Counters: dropped (must be 0), samples the main
// loop saw as newest, and the pose lag (newest sample age at each poll).
void BM_HalSustained1kHz(benchmark::State& state) {
  constexpr int kReports = 3000;
  for (auto _ : state) {
    FeedBackend backend;
    auto feed = attach_compact(backend);
    DeviceReader reader(1, open_compact(backend), compact_pipeline());
    reader.start();
    std::atomic<bool> done{false};
    std::thread device_thread([&] {
      const int64_t start = monotonic_ns();
      for (int k = 0; k < kReports; ++k) {
        const int64_t due = start + int64_t{k} * 1'000'000;
        while (monotonic_ns() < due)
          std::this_thread::sleep_for(std::chrono::microseconds(100));
        feed->push(compact_report(monotonic_ns(), k));
      }
      done = true;
    });
    PoseIntegrator integrator;
    InputFrame frame;
    int64_t frames = 0;
    while (!done.load() || reader.counters().raw_events < kReports) {
      std::this_thread::sleep_for(std::chrono::microseconds(16'667));
      frame.clear();
      reader.poll(frame, monotonic_ns());
      for (const InputEvent& e : frame.events) {
        if (e.kind == InputKind::kMotion) integrator.update(e);
      }
      ++frames;
    }
    device_thread.join();
    frame.clear();
    reader.poll(frame, monotonic_ns());
    reader.stop();
    const ReaderCounters c = reader.counters();
    state.counters["reports"] = static_cast<double>(c.raw_events);
    state.counters["motion_samples"] = static_cast<double>(c.motion_samples);
    state.counters["dropped"] = static_cast<double>(c.dropped);
    state.counters["late"] = static_cast<double>(c.late);
    state.counters["frames"] = static_cast<double>(frames);
    state.counters["rate_hz"] = static_cast<double>(c.raw_events) / 3.0;
  }
}
BENCHMARK(BM_HalSustained1kHz)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace sculpt::hal
