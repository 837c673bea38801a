#include "sculpt/station/app/session_replay.h"

#include <algorithm>
#include <chrono>

#include "sculpt/hal/input/device_stream.h"
#include "sculpt/hal/normalizer/normalizer_config.h"
#include "sculpt/hal/parsers/make_parser.h"
#include "sculpt/sim/replay/session_player.h"

namespace sculpt::station {

LatencyStats latency_stats(std::vector<double> us) {
  LatencyStats s;
  s.count = static_cast<int64_t>(us.size());
  if (us.empty()) return s;
  std::sort(us.begin(), us.end());
  auto at = [&](double q) {
    return us[std::min(us.size() - 1, static_cast<size_t>(q * static_cast<double>(us.size())))];
  };
  s.p50_us = at(0.50);
  s.p90_us = at(0.90);
  s.p99_us = at(0.99);
  s.max_us = us.back();
  return s;
}

LatencyStats latency_stats(const LatencyHistogram& us) {
  return {.count = us.count(),
          .p50_us = us.quantile_us(0.50),
          .p90_us = us.quantile_us(0.90),
          .p99_us = us.quantile_us(0.99),
          .max_us = us.max_us()};
}

Result<ReplayResult> replay_session(const sim::Session& session, const std::string& name,
                                    StationLoop& loop, const ReplayOptions& options) {
  const hal::DeviceInfo& device = session.header.device;
  auto config = hal::parse_normalizer_config(session.header.normalizer_config,
                                             name + " (normaliser settings)");
  if (!config) return config.error();
  auto first_parser = hal::make_parser(device);
  if (!first_parser) return Error(name + ": " + first_parser.error().message());
  // The live reader's stream: the device comes with its first record and
  // goes with a removal; one plugged back in gets a new parser and
  // normaliser with no memory of the buttons held before, as live.
  hal::DeviceStream stream(0, hal::MotionPipeline(std::move(first_parser).value(), *config),
                           [&device, normalizer = *config] {
                             return hal::MotionPipeline(hal::make_parser(device).value(),
                                                        normalizer);  // made once already
                           });

  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  sim::SessionPlayer player(session, options.speed, options.fast);
  std::vector<hal::InputEvent> events;
  LatencyHistogram latencies_us;  // fixed memory however long the session
  ReplayResult result;
  while (const sim::SessionRecord* r = player.next()) {
    ++result.records;
    if (r->kind == sim::SessionRecord::Kind::kCommand) {
      loop.handle(r->command);
      continue;
    }
    if (r->kind == sim::SessionRecord::Kind::kHaptic) {
      if (options.on_haptic) {
        if (Status st = options.on_haptic(r->haptic); !st) return st.error();
      }
      continue;
    }
    const auto t0 = clock::now();
    const int64_t dabs_before = loop.counters().dabs;
    events.clear();
    stream.feed(r->event, events);
    for (const hal::InputEvent& e : events) {
      loop.handle(e);
      if (options.on_sample) options.on_sample(e);
    }
    const int64_t new_dabs = loop.counters().dabs - dabs_before;
    if (new_dabs > 0) {
      loop.update_mesh();
      const double us = std::chrono::duration<double, std::micro>(clock::now() - t0).count();
      for (int64_t i = 0; i < new_dabs; ++i)
        latencies_us.add(us);
    }
  }
  loop.update_mesh();
  result.wall_seconds = std::chrono::duration<double>(clock::now() - start).count();
  result.session_seconds = static_cast<double>(session.end_t_ns() - session.start_t_ns()) * 1e-9;
  result.dab_latency = latency_stats(latencies_us);
  const hal::ParserCounters parsed = stream.parser_counters();
  result.unknown_reports = parsed.unknown_reports;
  result.short_reports = parsed.short_reports;
  result.invalid_reports = parsed.invalid_reports;
  return result;
}

}  // namespace sculpt::station
