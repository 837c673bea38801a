// sculpt record --device ID -o SESSION [--seconds S] [--speed X]
//
// Records a live device at the raw-report level into a binary session file,
// append-only (a crash or an unplug loses at most the last 0.25 s). Stops on
// Ctrl-C, when the device is unplugged, or after --seconds. `--device
// sim:FILE` records a session played as a live device (for tests without
// hardware; --speed plays it faster). `--device opentrack[:PORT]` or
// `vrpn:NAME@HOST[:PORT]` records a network tracker; an OpenTrack listener
// binds to loopback unless --listen names another address.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "cli/commands.h"
#include "cli/number_checks.h"
#include "sculpt/hal/normalizer/normalizer_config.h"
#include "sculpt/hal/registry/device_registry.h"
#include "sculpt/hal/registry/tracker_backends.h"
#include "sculpt/sim/replay/sim_backend.h"
#include "sculpt/sim/session/session_file.h"
#include "sculpt/station/app/session_loading.h"

namespace sculpt::station::cli {
namespace {

// How often the raw events the reader thread tapped are appended to the
// file. Each append is one write(2): once there, a killed process loses
// nothing (the kernel has it), so SIGKILL loses at most this much; the file
// is synced every SessionWriter::kSyncInterval for power cuts.
constexpr std::chrono::milliseconds kDrainInterval{10};
static_assert(kDrainInterval <= sim::SessionWriter::kSyncInterval);

struct RecordOptions {
  std::string device;
  std::string output;
  double seconds = 0;
  double speed = 1.0;
  std::string listen = "127.0.0.1";
};

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) {
  g_stop.store(true);
}

// Raw events from the reader thread to the main thread, which writes them.
class RawQueue {
 public:
  void push(const hal::RawEvent& e) {
    std::lock_guard lock(mutex_);
    events_.push_back(e);
  }
  std::deque<hal::RawEvent> take() {
    std::lock_guard lock(mutex_);
    return std::exchange(events_, {});
  }

 private:
  std::mutex mutex_;
  std::deque<hal::RawEvent> events_;
};

int run_record(const RecordOptions& o) {
  auto queue = std::make_shared<RawQueue>();
  hal::ReaderOptions reader_options;
  reader_options.on_raw = [queue](const hal::RawEvent& e) { queue->push(e); };
  auto config = hal::load_normalizer_config_or_defaults(hal::default_normalizer_config_path());
  if (!config) return report(config.error());
  std::optional<sim::Session> sim_session;
  if (o.device.rfind("sim:", 0) == 0) {
    const std::string file = o.device.substr(4);
    auto session = load_session(file);
    if (!session) return report(session.error());
    // A session plays through the normaliser settings it was recorded with,
    // as in the window and in its replay; the recording stores those, so it
    // replays to the same sculpture.
    auto recorded = hal::parse_normalizer_config(session->header.normalizer_config,
                                                 file + " (normaliser settings)");
    if (!recorded) return report(recorded.error());
    *config = *recorded;
    sim_session = std::move(session).value();
  }
  hal::DeviceRegistry registry(hal::DeviceRegistry::default_backends(), *config, reader_options);

  sim::SimBackend* sim_backend = nullptr;
  if (sim_session) {
    auto backend =
        std::make_unique<sim::SimBackend>(std::move(*sim_session), o.device.substr(4), o.speed);
    sim_backend = backend.get();
    registry.add_backend(std::move(backend), /*first=*/true);
  }
  auto device = hal::add_named_tracker(registry, o.device, o.listen);
  if (!device) return report(device.error());
  auto id = registry.open_device(*device);
  if (!id) return report(id.error());
  const hal::DeviceReader* reader = registry.reader(*id);

  sim::SessionHeader header;
  header.device = reader->info();
  header.normalizer_config = hal::to_text(*config);
  header.created_unix_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                               std::chrono::system_clock::now().time_since_epoch())
                               .count();
  auto writer = sim::SessionWriter::create(o.output, header);
  if (!writer) return report(writer.error());

  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::printf("recording %s (%s %s) to %s; Ctrl-C stops\n", header.device.id().c_str(),
              header.device.vendor_product().c_str(), header.device.name.c_str(), o.output.c_str());
  std::fflush(stdout);

  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  hal::InputFrame frame;
  bool gone = false;
  std::vector<sim::SessionRecord> batch;
  auto drain = [&]() -> Status {
    batch.clear();
    // Commands first, so a command and a report of the same time keep the
    // order the station saw them in; then a stable merge by time.
    if (sim_backend != nullptr) {
      for (const auto& [t, c] : sim_backend->take_commands())
        batch.push_back(sim::SessionRecord::of(t, c));
    }
    for (const hal::RawEvent& e : queue->take())
      batch.push_back(sim::SessionRecord::of(e));
    std::stable_sort(batch.begin(), batch.end(),
                     [](const sim::SessionRecord& a, const sim::SessionRecord& b) {
                       return a.t_ns() < b.t_ns();
                     });
    for (const sim::SessionRecord& r : batch) {
      if (Status st = writer->append(r); !st) return st;
    }
    return writer->sync_if_due();
  };
  while (!g_stop.load() && !gone) {
    std::this_thread::sleep_for(kDrainInterval);
    if (Status st = drain(); !st) return report(st.error());
    frame.clear();
    registry.poll(frame, 0);
    for (const hal::InputEvent& e : frame.events)
      gone |= e.kind == hal::InputKind::kDisconnected;
    if (o.seconds > 0 && std::chrono::duration<double>(clock::now() - start).count() >= o.seconds)
      break;
  }
  if (Status st = drain(); !st) return report(st.error());
  const int64_t records = writer->records();
  if (Status st = writer->close(); !st) return report(st.error());
  std::printf("recorded %lld records in %.1f s%s\n", static_cast<long long>(records),
              std::chrono::duration<double>(clock::now() - start).count(),
              gone ? " (the device was unplugged)" : "");
  return 0;
}

}  // namespace

void add_record_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<RecordOptions>();
  CLI::App* cmd = app.add_subcommand("record", "record a device's raw reports into a session file");
  cmd->add_option("--device", o->device,
                  "device id as `sculpt devices` prints it, a backend, vvvv:pppp, sim:FILE, "
                  "opentrack[:PORT] or vrpn:NAME@HOST[:PORT]")
      ->required();
  cmd->add_option("-o,--output", o->output, "session file to write (.scs)")->required();
  cmd->add_option("--seconds", o->seconds, "stop after this long")->check(finite_positive());
  cmd->add_option("--listen", o->listen,
                  "opentrack only: the address to listen on (another machine's tracker needs "
                  "this machine's address; anyone who can reach it can then move the tool)")
      ->capture_default_str();
  cmd->add_option("--speed", o->speed, "sim:FILE only: play the session this much faster")
      ->check(finite_positive());
  cmd->callback([o, &action] { action = [o] { return run_record(*o); }; });
}

}  // namespace sculpt::station::cli
