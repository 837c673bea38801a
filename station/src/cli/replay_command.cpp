// sculpt replay SESSION [--fast|--speed X] [--volume V.{nrrd,vdb}] [--mesh M.{ply,obj,stl,glb}]
//                       [--simplify R] [--max-error E] [--check [--voxel-mm S]] [--ascii]
//                       [--stats S.json] [--samples S.jsonl] [--forces F.jsonl]
//
// Replays a recorded session (binary or text) through the real parsers,
// normaliser, pose integration, stroke sampler, sculptor and mesh cache.

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/number_checks.h"
#include "cli/progress_bar.h"
#include "sculpt/base/atomic_file.h"
#include "sculpt/base/output_set.h"
#include "sculpt/core/distance/surface_normals.h"
#include "sculpt/core/files/volume_file.h"
#include "sculpt/core/mesh/mesh_io.h"
#include "sculpt/core/util/parallel_for.h"
#include "sculpt/core/volume/volume_io.h"
#include "sculpt/station/app/rotation_cache_figures.h"
#include "sculpt/station/app/session_loading.h"
#include "sculpt/station/app/session_replay.h"
#include "sculpt/station/app/session_start.h"
#include "sculpt/station/haptics/haptic_replay.h"
#include "sculpt/station/project/project_file.h"
#include "sculpt/station/render/software_renderer.h"
#include "sculpt/station/window/gl_snapshot.h"

namespace sculpt::station::cli {
namespace {

constexpr int kPictureSize = 800;  // pixels a side

nlohmann::json sample_json(const hal::InputEvent& e) {
  nlohmann::json j = {{"t", e.t_ns}, {"device", e.device_id}};
  switch (e.kind) {
    case hal::InputKind::kMotion:
      if (e.has_pose) {  // a tracker: its pose, not axes (decoded again from the recorded bytes)
        const hal::TrackerPose& p = e.pose;
        j["pose"] = {{"position_mm", p.position_mm}, {"quat", p.quat_wxyz}};
        if (p.sensor != 0) j["pose"]["sensor"] = p.sensor;
        break;
      }
      j["motion"] = e.axes;
      if (e.translation_stale) j["translation_stale"] = true;
      if (e.rotation_stale) j["rotation_stale"] = true;
      if (e.absolute) j["absolute"] = true;
      break;
    case hal::InputKind::kButton:
      j["button"] = {e.button, e.pressed ? 1 : 0};
      break;
    case hal::InputKind::kBattery:
      j["battery"] = {e.battery_percent, e.charging};
      break;
    case hal::InputKind::kConnected:
      j["connected"] = true;
      break;
    case hal::InputKind::kDisconnected:
      j["disconnected"] = true;
      break;
    case hal::InputKind::kTrackingLost:
      j["tracking_lost"] = true;
      break;
  }
  return j;
}

nlohmann::json vec_json(glm::vec3 v) {
  return {v.x, v.y, v.z};
}

// One tick of a force device's loop, run again.
nlohmann::json force_json(const ReplayedTick& r) {
  nlohmann::json j = {{"t", r.tick.t_ns},
                      {"loop", r.loop},
                      {"index", r.tick.index},
                      {"position_mm", vec_json(r.tick.position_mm)},
                      {"buttons", r.tick.buttons},
                      {"force_n", vec_json(r.tick.force_n)},
                      {"proxy_vox", vec_json(r.contact.proxy_vox)},
                      {"contact", r.contact.contact}};
  if (!r.matches) j["differs_from_recording"] = true;
  return j;
}

nlohmann::json haptics_json(const HapticReplayFigures& f) {
  return {{"loops", f.loops},
          {"ticks", f.ticks},
          {"force_mismatches", f.force_mismatches},
          {"unverified_ticks", f.unverified_ticks},
          {"patches", f.patches},
          {"patch_mismatches", f.patch_mismatches},
          {"late_ticks", f.late_ticks},
          {"worst_period_us", f.worst_period_us},
          {"period_p99_us", f.period_p99_us},
          {"max_force_n", f.max_force_n}};
}

}  // namespace

int replay_to_outputs(const ReplayCliOptions& o) {
  core::set_default_threads(o.threads);
  // Check every output's format before the (possibly long) replay.
  std::optional<core::MeshFormat> mesh_format;
  if (!o.mesh.empty()) {
    auto f = mesh_export_format(o.mesh, o.mesh_export);
    if (!f) return report(f.error());
    mesh_format = *f;
  }
  sim::SessionReadInfo info;
  auto session = load_session(o.session, &info);
  if (!session) return report(session.error());
  if (!info.warning.empty()) std::fprintf(stderr, "sculpt: warning: %s\n", info.warning.c_str());

  std::string samples_text;
  ReplayOptions options;
  options.speed = o.speed;
  options.fast = o.fast;
  if (!o.samples.empty()) {
    options.on_sample = [&](const hal::InputEvent& e) {
      samples_text += sample_json(e).dump() + "\n";
    };
  }
  // The session's volume command sizes the block; nobody watches a replay's
  // brushes as they go, and the result is the same without.
  StationLoop::Options loop_options;
  loop_options.preview_brushes = false;
  StationLoop loop(loop_options);
  // A force device's loops run again on the replayed material.
  HapticReplay haptics(loop, o.session);
  std::string forces_text;
  options.on_haptic = [&](const sim::HapticRecord& r) { return haptics.handle(r); };
  if (!o.forces.empty()) {
    haptics.on_tick = [&](const ReplayedTick& t) { forces_text += force_json(t).dump() + "\n"; };
  }
  // A recording started on a sculpture replays onto it (session_start.h).
  if (auto started = restore_session_start(o.session, loop); !started) {
    return report(started.error());
  }
  // --fast replays can take minutes (the 512^3 bust): progress by session
  // time, on a terminal only (scripts check that a bad output is one line
  // on stderr, and replay finds it after the work). The replay cannot stop
  // early (it is the station's own loop), so Ctrl-C keeps its usual effect:
  // the process ends, nothing is written.
  std::optional<ProgressBar> bar;
  if (o.fast && isatty(STDERR_FILENO) != 0) {
    bar.emplace("replay", ProgressBar::CtrlC::kDefault);
    const int64_t start = session->start_t_ns(), span = session->end_t_ns() - start;
    options.on_sample = [&, sample = std::move(options.on_sample)](const hal::InputEvent& e) {
      if (sample) sample(e);
      if (span > 0) bar->progress()->report(double(e.t_ns - start) / double(span));
    };
  }
  auto result = replay_session(*session, o.session, loop, options);
  if (bar) bar->finish();
  if (!result) return report(result.error());

  const core::Volume& volume = loop.volume();
  const uint64_t hash = volume.content_hash();
  const StationCounters& c = loop.counters();
  nlohmann::json stats = {
      {"session", o.session},
      {"records", result->records},
      {"records_lost_bytes", info.bytes_lost},
      {"dabs", c.dabs},
      {"strokes", c.strokes},
      {"motion_samples", c.motion_samples},
      {"undos", c.undos},
      {"redos", c.redos},
      {"disconnects", c.disconnects},
      {"tracking_losses", c.tracking_losses},
      {"volume_dims", {volume.dims().x, volume.dims().y, volume.dims().z}},
      {"volume_hash", hash},
      {"triangles", loop.mesh().triangle_count()},
      {"dab_latency_us",
       {{"count", result->dab_latency.count},
        {"p50", result->dab_latency.p50_us},
        {"p90", result->dab_latency.p90_us},
        {"p99", result->dab_latency.p99_us},
        {"max", result->dab_latency.max_us}}},
      {"replay_seconds", result->wall_seconds},
      {"session_seconds", result->session_seconds},
      {"speedup", result->wall_seconds > 0 ? result->session_seconds / result->wall_seconds : 0.0},
      {"unknown_reports", result->unknown_reports},
      {"short_reports", result->short_reports},
      {"invalid_reports", result->invalid_reports},
      {"rotation_cache", rotation_cache_figures(loop.rotation_cache_stats())},
  };
  const HapticReplayFigures haptic = haptics.figures();
  if (haptic.loops > 0 || haptic.unverified_ticks > 0) stats["haptics"] = haptics_json(haptic);
  // Every output or none: each is staged whole, and all are moved into
  // place once the last one is written.
  OutputSet outputs;
  const auto failed = [&](const Status& st) { return report(outputs.named(st.error())); };
  if (!o.volume.empty()) {
    if (Status st = core::write_volume_file(outputs.stage(o.volume), volume); !st) {
      return failed(st);
    }
  }
  core::Mesh mesh = loop.mesh().welded_mesh();
  if (o.normals == "distance" && (mesh_format || !o.png.empty())) {
    const auto t0 = std::chrono::steady_clock::now();
    core::set_normals_from_surface_distance(volume, mesh);
    stats["distance_normals_seconds"] =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  if (mesh_format) {
    // Simplified and checked for the file only: the picture shows the full mesh.
    const auto exported = prepare_mesh_export(mesh, o.mesh_export, o.mesh + ": not written");
    if (!exported) return report(exported.error());
    if (Status st = core::write_mesh(outputs.stage(o.mesh), *exported, *mesh_format); !st) {
      return failed(st);
    }
  }
  if (!o.png.empty()) {
    // The station's GL renderer through an invisible window when there is a
    // display; the CPU rasteriser otherwise.
    const bool gl = o.renderer == "gl" || (o.renderer == "auto" && display_available());
    RgbImage image;
    // Either way framed on the sculpture (the whole block when it is
    // empty); the GL picture draws the block's edges and grid around it.
    const SoftwareView framed = view_of(mesh, glm::vec3(0.0f), glm::vec3(volume.dims()));
    if (gl) {
      auto picture = render_mesh_gl(mesh, GlPictureView{glm::vec3(volume.dims()), framed.box_lo,
                                                        framed.box_hi, kPictureSize, kPictureSize});
      if (!picture) return report(Error("--png " + o.png + ": " + picture.error().message()));
      image = std::move(picture).value();
    } else {
      image = render_mesh(mesh, framed);
    }
    stats["renderer"] = gl ? "gl" : "software";
    if (Status st = write_png(outputs.stage(o.png), image); !st) return failed(st);
  }
  if (!o.project.empty()) {
    const StationSettings& settings = loop.settings();
    // Opened, the project shows its sculpture framed, as a session's start
    // does (the default view looks at a 256^3 block's centre).
    OrbitCamera camera;
    camera.frame_material(volume);
    if (Status st =
            save_project(outputs.stage(o.project), volume, settings,
                         settings.custom_tool ? &loop.tool() : nullptr, project_view(camera));
        !st) {
      return failed(st);
    }
  }
  if (!o.samples.empty()) {
    AtomicFileWriter out(outputs.stage(o.samples));
    out.write(samples_text);
    if (Status st = out.commit(); !st) return failed(st);
  }
  if (!o.forces.empty()) {
    AtomicFileWriter out(outputs.stage(o.forces));
    out.write(forces_text);
    if (Status st = out.commit(); !st) return failed(st);
  }
  if (!o.stats.empty()) {
    AtomicFileWriter out(outputs.stage(o.stats));
    out.write(stats.dump(2) + "\n");
    if (Status st = out.commit(); !st) return failed(st);
  }
  if (Status st = outputs.commit(); !st) return report(st.error());
  std::printf(
      "replayed %s: %lld records, %lld dabs in %lld strokes, %lld triangles, %.2f s (%.1fx real "
      "time)\n",
      o.session.c_str(), static_cast<long long>(result->records), static_cast<long long>(c.dabs),
      static_cast<long long>(c.strokes), static_cast<long long>(loop.mesh().triangle_count()),
      result->wall_seconds, stats["speedup"].get<double>());
  std::printf("volume hash %016llx\n", static_cast<unsigned long long>(hash));
  if (haptic.loops > 0) {
    std::printf(
        "force device: %lld loops, %lld ticks run again, %lld forces differ from the "
        "recording, %lld ticks not verifiable\n",
        static_cast<long long>(haptic.loops), static_cast<long long>(haptic.ticks),
        static_cast<long long>(haptic.force_mismatches),
        static_cast<long long>(haptic.unverified_ticks));
  }
  return 0;
}

void add_replay_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<ReplayCliOptions>();
  CLI::App* cmd = app.add_subcommand("replay", "replay a recorded session through the station");
  cmd->add_option("session", o->session, "session file (.scs binary or .jsonl text)")
      ->required()
      ->check(input_file());
  auto* fast = cmd->add_flag("--fast", o->fast, "as fast as possible");
  cmd->add_option("--speed", o->speed, "speed factor (1 = real time)")
      ->check(finite_positive())
      ->excludes(fast);
  cmd->add_option("--threads", o->threads,
                  "threads for volume work (0 = all cores); never changes the result")
      ->check(finite_range(0, 256));
  cmd->add_option("--volume", o->volume, "write the resulting volume (.nrrd, or .vdb: OpenVDB)");
  cmd->add_option("--mesh", o->mesh, "write the resulting surface (.ply, .obj, .stl, .glb)");
  add_mesh_export_options(cmd, o->mesh_export);
  cmd->add_option("--png", o->png, "write a picture of the result (PNG)");
  cmd->add_option("--renderer", o->renderer,
                  "for --png: gl (an invisible window), software (no display needed), or auto "
                  "(gl when there is a display)")
      ->check(CLI::IsMember({"auto", "gl", "software"}))
      ->capture_default_str();
  cmd->add_option("--normals", o->normals,
                  "normals of --mesh and --png: density (its gradient, as drawn live) or distance "
                  "(the gradient of the distance to the sub-voxel surface, Jones & Satherley)")
      ->check(CLI::IsMember({"density", "distance"}))
      ->capture_default_str();
  cmd->add_option("--stats", o->stats,
                  "write statistics (JSON): dabs, volume hash, triangles, latency, haptic loops");
  cmd->add_option("--project", o->project,
                  "write the final state as a project the station opens (.sculpt)");
  cmd->add_option("--samples", o->samples, "write the decoded, normalised samples (JSON Lines)");
  cmd->add_option("--forces", o->forces,
                  "write the force device's ticks, run again: position, buttons, force, proxy "
                  "(JSON Lines)");
  cmd->callback([o, &action] { action = [o] { return replay_to_outputs(*o); }; });
}

}  // namespace sculpt::station::cli
