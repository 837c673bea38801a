// Tracker benchmarks (issue 22): datagram or message to pose, target p99
// well under 50 us. The decoders alone (OpenTrack datagram; VRPN framing and
// Pos_Quat), and the OpenTrack receiver over a real loopback socket, from
// sendto() to the decoded pose, one datagram in flight.
//
// Latencies are measured per datagram with the monotonic clock and reported
// as counters (median_us, p99_us, max_us); the iteration time of Google
// Benchmark is the throughput, not the latency.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <benchmark/benchmark.h>

#include <vector>

#include "sculpt/base/latency_histogram.h"
#include "sculpt/hal/backends/opentrack_backend.h"
#include "sculpt/hal/parsers/opentrack_datagram.h"
#include "sculpt/hal/parsers/vrpn_message.h"
#include "sculpt/hal/types/clock.h"

namespace sculpt::hal {
namespace {

void set_percentiles(benchmark::State& state, const LatencyHistogram& h) {
  state.counters["median_us"] = h.quantile_us(0.5);
  state.counters["p99_us"] = h.quantile_us(0.99);
  state.counters["max_us"] = h.max_us();
  state.counters["poses"] = static_cast<double>(h.count());
}

void BM_OpenTrackDatagramToPose(benchmark::State& state) {
  const auto datagram = encode_opentrack_datagram(1.5, -2.0, 30.0, 12.0, -5.0, 3.0);
  LatencyHistogram latency;
  TrackerPose pose;
  for (auto _ : state) {
    const int64_t t0 = monotonic_ns();
    benchmark::DoNotOptimize(decode_opentrack_datagram(datagram, pose));
    benchmark::DoNotOptimize(pose);
    latency.add(static_cast<double>(monotonic_ns() - t0) * 1e-3);
  }
  set_percentiles(state, latency);
}
BENCHMARK(BM_OpenTrackDatagramToPose);

// One framed Pos_Quat message as it sits in the client's buffer: frame it,
// then decode the payload.
void BM_VrpnMessageToPose(benchmark::State& state) {
  const auto message =
      encode_vrpn_message(5, 2, encode_vrpn_pos_quat(1, {0.1, 0.2, 0.3}, {0, 0, 0.6, 0.8}));
  LatencyHistogram latency;
  TrackerPose pose;
  for (auto _ : state) {
    const int64_t t0 = monotonic_ns();
    VrpnMessage m;
    if (next_vrpn_message(message, m) == VrpnFrameResult::kMessage)
      benchmark::DoNotOptimize(decode_vrpn_pos_quat(m.payload, pose));
    benchmark::DoNotOptimize(pose);
    latency.add(static_cast<double>(monotonic_ns() - t0) * 1e-3);
  }
  set_percentiles(state, latency);
}
BENCHMARK(BM_VrpnMessageToPose);

// The live path on one thread: sendto() on loopback, the receiver's poll and
// drain, the decoder.
void BM_OpenTrackLoopbackToPose(benchmark::State& state) {
  OpenTrackOptions options;
  options.port = 0;
  auto device = OpenTrackDevice::open(options);
  if (!device) {
    state.SkipWithError(device.error().message().c_str());
    return;
  }
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons((*device)->bound_port());
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  LatencyHistogram latency;
  int64_t lost = 0;
  int i = 0;
  for (auto _ : state) {
    const auto datagram = encode_opentrack_datagram(i++ % 100, 0, 0, 0, 0, 0);
    const int64_t t0 = monotonic_ns();
    ::sendto(fd, datagram.data(), datagram.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to);
    RawEvent raw;
    TrackerPose pose;
    if ((*device)->read(raw, 100) != ReadResult::kEvent ||
        decode_opentrack_datagram(raw.bytes(), pose) != OpenTrackDatagramError::kNone) {
      ++lost;
      continue;
    }
    benchmark::DoNotOptimize(pose);
    latency.add(static_cast<double>(monotonic_ns() - t0) * 1e-3);
  }
  ::close(fd);
  set_percentiles(state, latency);
  state.counters["lost"] = static_cast<double>(lost);
}
BENCHMARK(BM_OpenTrackLoopbackToPose)->Iterations(20000)->UseRealTime();

}  // namespace
}  // namespace sculpt::hal
