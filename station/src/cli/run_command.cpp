// sculpt run [--device auto|sim:FILE|ID] [--headless] [--open PROJECT] [--record FILE] ...
//
// The station. With a display it opens the window: a 3D mouse if one is
// attached (else the bundled demo session played as a live device), and the
// ordinary mouse and keyboard. With --headless, or no display, it runs the
// same loop without a window on a session (the demo by default) and writes
// what it made to DIR: sculpture.png, sculpture.ply, volume.nrrd, stats.json.

#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/number_checks.h"
#include "sculpt/hal/pose/tracker_axes.h"
#include "sculpt/sim/synth/bundled_sessions.h"
#include "sculpt/station/window/gl_snapshot.h"
#include "sculpt/station/window/station_window.h"

namespace sculpt::station::cli {
namespace {

struct RunOptions {
  WindowOptions window;
  bool headless = false;
  std::string out_dir = "sculpt-out";
};

int run_headless(const RunOptions& o) {
  namespace fs = std::filesystem;
  std::string session;
  if (o.window.device.rfind("sim:", 0) == 0) {
    session = o.window.device.substr(4);
  } else if (o.window.device == "auto") {
    session = sim::bundled_session_path("demo");
  } else {
    return report(Error("--device " + o.window.device +
                        ": a live device needs the window; headless runs replay sessions "
                        "(auto or sim:FILE; record one with `sculpt record`)"));
  }
  std::error_code ec;
  fs::create_directories(o.out_dir, ec);
  if (ec) return report(Error(o.out_dir + ": cannot create the output folder: " + ec.message()));
  const fs::path dir(o.out_dir);
  ReplayCliOptions r;
  r.session = session;
  r.fast = true;
  r.png = (dir / "sculpture.png").string();
  r.mesh = (dir / "sculpture.ply").string();
  r.volume = (dir / "volume.nrrd").string();
  r.stats = (dir / "stats.json").string();
  r.renderer = "software";  // no display here, or none wanted
  // The density gradient's normals (the default): at full detail the
  // truest (0.1 degrees off a sphere's on average, against 0.25 for the
  // distance field's), and no second spent on them.
  const int code = replay_to_outputs(r);
  if (code == 0) {
    std::printf("wrote %s/sculpture.png, sculpture.ply, volume.nrrd and stats.json\n",
                o.out_dir.c_str());
  }
  return code;
}

int run_station(const RunOptions& o) {
  if ((o.headless || !display_available()) && !o.window.haptic.empty())
    return report(
        Error("--haptic " + o.window.haptic + ": a force device needs the window (and a display)"));
  if (o.headless) return run_headless(o);
  if (!display_available()) {
    std::printf("no display: running headless (see --out)\n");
    return run_headless(o);
  }
  return run_window(o.window);
}

}  // namespace

void add_run_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand(
      "run", "the station: a window with a display, else the demo session headless");
  WindowOptions& w = o->window;
  cmd->add_option("--device", w.device,
                  "auto (a 3D mouse if attached, else the demo session), sim:FILE, a device "
                  "id as `sculpt devices` prints it, opentrack[:PORT] or vrpn:NAME@HOST[:PORT]")
      ->capture_default_str();
  cmd->add_option("--listen", w.listen,
                  "window, opentrack: the address to listen on (another machine's tracker needs "
                  "this machine's address; anyone who can reach it can then move the tool)")
      ->capture_default_str();
  cmd->add_flag("--headless", o->headless, "no window: replay the session and write --out");
  cmd->add_option("--out", o->out_dir, "headless: folder for the results")->capture_default_str();
  cmd->add_option("--open", w.project, "window: open this project (.sculpt)")->check(input_file());
  cmd->add_option("--record", w.record, "window: record the session to this file (.scs)");
  cmd->add_flag("--loop", w.sim_loop,
                "window, sim devices: play the session over and over (soak runs; never "
                "'replayed', so stop it with --frames or a signal)");
  cmd->add_option("--speed", w.sim_speed, "window, sim devices: play the session this much faster")
      ->check(finite_positive());
  cmd->add_option("--mesh-threads", w.mesh_threads,
                  "window: threads meshing the surface's changes (0: all cores)")
      ->capture_default_str()
      ->check(finite_range(0, 256));
  cmd->add_option("--simplify-error", w.simplify_error,
                  "window: how far simplifying may move the drawn surface, in voxels of each "
                  "brick's level (0: draw the marching-cubes meshes as they are)")
      ->capture_default_str()
      ->check(finite_range(0, 2));
  cmd->add_option("--undo-mib", w.undo_mib,
                  "window: memory for undo, MiB; the oldest strokes go beyond it")
      ->capture_default_str()
      ->check(finite_range(1, 65536));
  cmd->add_option("--frames", w.frames, "window: stop after this many frames")
      ->check(finite_positive());
  cmd->add_flag("--until-replayed", w.exit_when_replayed,
                "window: stop when the sim device goes (its session played, or unplugged in it); "
                "with no session, when a simulated arm's hand script unplugs it");
  cmd->add_option("--stats", w.stats, "window: write frame times and dab latency (JSON) at exit");
  cmd->add_option("--stats-every", w.stats_every_s,
                  "window: also rewrite --stats every this many seconds (a long run's monitor)")
      ->check(finite_range(0.1, 86400));
  cmd->add_option("--screenshot", w.screenshot,
                  "window: PNG of the last frame (with --frames or --until-replayed)");
  cmd->add_option_function<std::string>(
         "--normals",
         [&w = *o](const std::string& v) { w.window.distance_normals = v == "distance"; },
         "window: shading normals, density (its gradient, the default) or distance (the distance "
         "field's gradient; also in the panel's View section)")
      ->check(CLI::IsMember({"density", "distance"}));
  cmd->add_option_function<std::string>(
         "--size",
         [&w = *o](const std::string& v) {
           std::sscanf(v.c_str(), "%dx%d", &w.window.width, &w.window.height);
         },
         "window: its size in pixels, WIDTHxHEIGHT (default 1280x800)")
      ->check(
          [](const std::string& v) -> std::string {
            int width = 0, height = 0;
            char end = 0;
            if (std::sscanf(v.c_str(), "%dx%d%c", &width, &height, &end) != 2 || width < 64 ||
                height < 64 || width > 16384 || height > 16384)
              return "expected WIDTHxHEIGHT, each 64 to 16384 pixels";
            return {};
          },
          "WIDTHxHEIGHT");
  cmd->add_option("--haptic", w.haptic,
                  "window: a force device beside the pointing device: falcon[:USB_LOCATION] (a "
                  "Novint Falcon) or sim-arm:HAND_SCRIPT (the simulated arm held by a scripted "
                  "hand)");
  cmd->add_option("--falcon-firmware", w.falcon_firmware,
                  "window: the Novint firmware file a Falcon needs once per power-up (yours: it "
                  "is not shipped and never downloaded)")
      ->check(input_file());
  cmd->add_option("--haptic-stiffness", w.haptic_stiffness_n_per_mm,
                  "window: the material's stiffness under a force device, N/mm (clamped to the "
                  "device's limit)")
      ->capture_default_str()
      ->check(finite_range(0.01, 100));
  cmd->add_option("--haptic-spin-us", w.haptic_spin_us,
                  "window: the haptic thread wakes this many microseconds before each 1 ms "
                  "tick and polls the clock to it, absorbing late wake-ups for that share of a "
                  "core")
      ->capture_default_str()
      ->check(CLI::Range(0, 500));
  cmd->add_option("--haptic-standby", w.haptic_standby,
                  "window: a second haptic thread on another core wakes at the same deadlines "
                  "and runs a tick the first wakes late for (on, or off: one thread)")
      ->capture_default_str()
      ->transform(
          CLI::CheckedTransformer(std::map<std::string, bool>{{"on", true}, {"off", false}}));
  cmd->add_option("--workspace-scale", w.workspace_scale,
                  "window: material millimetres per force-device millimetre")
      ->capture_default_str()
      ->check(finite_range(0.01, 100));
  cmd->add_option("--tracker-scale", w.tracker.scale_vox_per_mm,
                  "window, trackers: voxels per millimetre of tracker motion (Home then sets "
                  "where the sculpture's centre is: hold the tracker there and press it)")
      ->capture_default_str()
      ->check(finite_range(0.001, 1000));
  cmd->add_option_function<std::string>(
         "--tracker-axes",
         [&w = *o](const std::string& v) {
           w.window.tracker.tracker_to_sculpture = hal::parse_tracker_axes(v).value();
         },
         "window, trackers: the tracker's axes that become the sculpture's x, y and z, e.g. "
         "x,z,-y for a tracker whose z is up (default x,y,z)")
      ->check(
          [](const std::string& v) -> std::string {
            const Result<glm::dquat> axes = hal::parse_tracker_axes(v);
            return axes.ok() ? std::string() : axes.error().message();
          },
          "AXES");
  cmd->add_option("--voxel-mm", w.voxel_mm, "window: the material's voxel size, mm")
      ->capture_default_str()
      ->check(finite_range(0.001, 100));
  cmd->add_option("--lod", w.lod, "window: draw every brick at this level (default: by distance)")
      ->check(finite_range(0, 2));
  cmd->add_flag(
      "--no-vsync", [&w = *o](int64_t) { w.window.vsync = false; },
      "window: draw as fast as possible (to measure frame rates)");
  cmd->add_flag(
      "--no-stand-ins", [&w = *o](int64_t) { w.window.stand_ins = false; },
      "window: show a dab only once it is meshed, not at once by the tool's mesh where it "
      "landed (to compare)");
  cmd->add_flag(
      "--hidden", [&w = *o](int64_t) { w.window.visible = false; },
      "window: do not show it (tests, benchmarks)");
  cmd->callback([o, &action] { action = [o] { return run_station(*o); }; });
}

}  // namespace sculpt::station::cli
