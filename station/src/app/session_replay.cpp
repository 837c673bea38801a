#include "sculpt/station/app/session_replay.h"

#include <algorithm>
#include <chrono>

#include "sculpt/hal/input/motion_pipeline.h"
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

namespace {

hal::InputEvent lifecycle_event(hal::InputKind kind, int64_t t_ns) {
  hal::InputEvent e;
  e.kind = kind;
  e.t_ns = t_ns;
  return e;
}

}  // namespace

Result<ReplayResult> replay_session(const sim::Session& session, const std::string& name,
                                          StationLoop& loop, const ReplayOptions& options) {
  const hal::DeviceInfo& device = session.header.device;
  auto config = hal::parse_normalizer_config(session.header.normalizer_config,
                                             name + " (normaliser settings)");
  if (!config) return config.error();
  // A re-plugged device gets a new reader, hence a new parser and normaliser
  // with no memory of the buttons held before: so does its replay.
  auto make_pipeline = [&]() -> Result<std::unique_ptr<hal::MotionPipeline>> {
    auto parser = hal::make_parser(device);
    if (!parser) return Error(name + ": " + parser.error().message());
    return std::make_unique<hal::MotionPipeline>(std::move(parser).value(), *config);
  };
  auto first = make_pipeline();
  if (!first) return first.error();
  std::unique_ptr<hal::MotionPipeline> pipeline = std::move(first).value();
  hal::ParserCounters parsed;
  auto add_counters = [&](const hal::ParserCounters& c) {
    parsed.unknown_reports += c.unknown_reports;
    parsed.short_reports += c.short_reports;
  };

  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  sim::SessionPlayer player(session, options.speed, options.fast);
  std::vector<hal::InputEvent> events;
  std::vector<double> latencies_us;
  ReplayResult result;
  bool connected = false;
  while (const sim::SessionRecord* r = player.next()) {
    ++result.records;
    if (r->kind == sim::SessionRecord::Kind::kCommand) {
      loop.handle(r->command);
      continue;
    }
    const auto t0 = clock::now();
    const int64_t dabs_before = loop.counters().dabs;
    events.clear();
    pipeline->feed(r->event, 0, events);
    // What the live reader thread adds around the parser: the device comes
    // (its first record, or the first after a removal) and goes.
    if (r->event.kind == hal::RawEventKind::kRemoved) {
      events.push_back(lifecycle_event(hal::InputKind::kDisconnected, r->event.t_ns));
      connected = false;
      add_counters(pipeline->parser_counters());
      pipeline = std::move(make_pipeline()).value();  // the device made one already
    } else if (!connected) {
      events.insert(events.begin(), lifecycle_event(hal::InputKind::kConnected, r->event.t_ns));
      connected = true;
    }
    for (const hal::InputEvent& e : events) {
      loop.handle(e);
      if (options.on_sample) options.on_sample(e);
    }
    const int64_t new_dabs = loop.counters().dabs - dabs_before;
    if (new_dabs > 0) {
      loop.update_mesh();
      const double us = std::chrono::duration<double, std::micro>(clock::now() - t0).count();
      latencies_us.insert(latencies_us.end(), static_cast<size_t>(new_dabs), us);
    }
  }
  loop.update_mesh();
  result.wall_seconds = std::chrono::duration<double>(clock::now() - start).count();
  result.session_seconds = static_cast<double>(session.end_t_ns() - session.start_t_ns()) * 1e-9;
  result.dab_latency = latency_stats(std::move(latencies_us));
  add_counters(pipeline->parser_counters());
  result.unknown_reports = parsed.unknown_reports;
  result.short_reports = parsed.short_reports;
  return result;
}

}  // namespace sculpt::station
