// sculpt run [--device auto|sim:FILE] [--headless] [--out DIR]
//
// The station's main job. With no device attached it replays the bundled
// demo session (sim/sessions/demo.scs) through the whole station and writes
// what it made to DIR: sculpture.png (rendered without a display),
// sculpture.ply, volume.nrrd and stats.json. `--device sim:FILE` replays
// another session. The live window and hardware devices arrive with the
// station issue; until then `--device auto` with a device attached says so.

#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli/commands.h"
#include "sculpt/hal/device/device_registry.h"
#include "sculpt/sim/synth/bundled_sessions.h"

namespace sculpt::station::cli {
namespace {

struct RunOptions {
  std::string device = "auto";
  bool headless = false;
  std::string out_dir = "sculpt-out";
};

int run_station(const RunOptions& o) {
  namespace fs = std::filesystem;
  std::string session;
  if (o.device.rfind("sim:", 0) == 0) {
    session = o.device.substr(4);
  } else if (o.device == "auto") {
    session = sim::bundled_session_path("demo");
    hal::DeviceRegistry registry(hal::DeviceRegistry::default_backends());
    for (const hal::BackendListing& b : registry.list()) {
      if (!b.devices.empty()) {
        std::printf(
            "found %s on %s; the live window is not built yet, replaying the demo session "
            "instead\n",
            b.devices.front().name.c_str(), b.backend.c_str());
        break;
      }
    }
  } else {
    return report(core::Error(
        "--device " + o.device +
        ": live devices need the station window (not built yet); use sim:FILE or auto"));
  }
  std::error_code ec;
  fs::create_directories(o.out_dir, ec);
  if (ec)
    return report(core::Error(o.out_dir + ": cannot create the output folder: " + ec.message()));
  const fs::path dir(o.out_dir);
  ReplayCliOptions r;
  r.session = session;
  r.fast = true;
  r.png = (dir / "sculpture.png").string();
  r.mesh = (dir / "sculpture.ply").string();
  r.volume = (dir / "volume.nrrd").string();
  r.stats = (dir / "stats.json").string();
  const int code = replay_to_outputs(r);
  if (code == 0) {
    std::printf("wrote %s/sculpture.png, sculpture.ply, volume.nrrd and stats.json\n",
                o.out_dir.c_str());
  }
  return code;
}

}  // namespace

void add_run_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd =
      app.add_subcommand("run", "run the station's main job (the demo session, headless)");
  cmd->add_option("--device", o->device, "auto (the demo session) or sim:FILE (a recorded session)")
      ->capture_default_str();
  cmd->add_flag("--headless", o->headless, "no window (the only mode until the window exists)");
  cmd->add_option("--out", o->out_dir, "folder for the results")->capture_default_str();
  cmd->callback([o, &action] { action = [o] { return run_station(*o); }; });
}

}  // namespace sculpt::station::cli
