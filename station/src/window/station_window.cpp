#include "sculpt/station/window/station_window.h"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <malloc.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "render/gl/scene_renderer.h"
#include "sculpt/base/atomic_file.h"
#include "sculpt/base/latency_histogram.h"
#include "sculpt/base/memory_reuse.h"
#include "sculpt/base/thread_priority.h"
#include "sculpt/base/thread_times.h"
#include "sculpt/core/util/parallel_for.h"
#include "sculpt/core/volume/material_bounds.h"
#include "sculpt/hal/normalizer/normalizer_config.h"
#include "sculpt/hal/registry/device_registry.h"
#include "sculpt/hal/registry/force_devices.h"
#include "sculpt/hal/registry/tracker_backends.h"
#include "sculpt/hal/types/clock.h"
#include "sculpt/sim/replay/sim_backend.h"
#include "sculpt/sim/synth/bundled_sessions.h"
#include "sculpt/station/app/input_hub.h"
#include "sculpt/station/app/rotation_cache_figures.h"
#include "sculpt/station/app/session_loading.h"
#include "sculpt/station/app/session_start.h"
#include "sculpt/station/app/station_controller.h"
#include "sculpt/station/haptics/haptic_station.h"
#include "sculpt/station/haptics/recorded_force_device.h"
#include "sculpt/station/render/software_renderer.h"
#include "sculpt/station/view/surface_mesher.h"
#include "sculpt/station/window/keymap.h"
#include "sculpt/station/window/panel_layer.h"
#include "window/gl_context.h"
#include "window/pointer_steering.h"
#include "window/station_panel.h"
#include "window/window_events.h"

namespace sculpt::station {
namespace {

constexpr int kMaxDrawnLevel = 2;  // coarser than 1/4 resolution looks like a blob
// The mesher's heap, touched when it starts (SurfaceMesher). 32 MiB was
// more than the demo's first big dab's meshes took (14 MB), but the 512^3
// bust's updates still faulted 6-13.5k pages a run (8 us each here); with
// 96 MiB, 0-2 in five runs of six, and its first-mesh latency fell from p99
// 78-116 ms, max 97-172 ms to p99 54-78 ms, max 92-126 ms (five pairs).
// The refiner's too: the demo's new block's refinement took 4,700 faults
// in the session's first half second, beside its first big balls.
constexpr size_t kMesherWarmHeapBytes = size_t{96} << 20;
// The pool's threads, which every parallel loop of the sculpting, meshing and
// refining shares: 1,800 faults a demo session before, most in its first
// second, while the first big balls were sculpted and meshed; with 16 MiB,
// 3,100 more while the bust's 110-voxel ball was sculpted and meshed.
constexpr size_t kPoolThreadWarmHeapBytes = size_t{48} << 20;
// The niceness of the frame's thread and the OpenGL driver's (thread_priority.h).
constexpr int kDrawingNice = 5;
// The real-time priorities (SCHED_FIFO) of the threads a dab's latency runs
// through, below the force loop's (80, HapticLoopOptions): a report first
// (a report that waits for its reader is latency no figure shows), then the
// sculpting, then the meshing, whose pool helpers take on its priority in
// its loops (parallel_for.h).
constexpr int kReaderRealtime = 4;
constexpr int kSculptingRealtime = 3;
constexpr int kMeshingRealtime = 2;

// Makes the sculpting thread and the mesher real-time (thread_priority.h);
// returns "" or why one could not be. (The device readers make themselves
// real-time as they start, ReaderOptions: a device plugged in later too.)
std::string make_dab_path_realtime() {
  const std::pair<const char*, int> threads[] = {{"sculpting", kSculptingRealtime},
                                                 {"mesher", kMeshingRealtime}};
  for (const auto& [name, priority] : threads)
    if (std::string why_not = make_threads_realtime(threads_named(name), priority);
        !why_not.empty())
      return std::string(name) + ": " + why_not;
  return {};
}

int fail(const Error& e) {
  std::fprintf(stderr, "sculpt run: %s\n", e.message().c_str());
  return 1;
}

// Frame and latency figures for --stats.
struct RunFigures {
  LatencyHistogram frame_us;  // fixed memory: the window runs for hours
  MesherCounters mesher;
  double frames_total_ms = 0;
  int64_t uploads = 0;
  int64_t triangles = 0;  // drawn in the last frame
  // Where the frames' time went, milliseconds summed over all frames.
  double input_ms = 0, mesh_ms = 0, upload_ms = 0, draw_ms = 0;
  int64_t started_ns = 0;              // the first frame's start
  int64_t frames_drawn_unsteered = 0;  // the sculpting thread held the turn: drawn without it
  int64_t panel_rasters = 0;           // frames that drew the panel's triangles (PanelLayer)
  // The last frame of --until-replayed waits for the sculpting thread's
  // turn and for every mesh, so that its picture (and the run's hash and
  // screenshot) holds the whole session: a wait for the run's report, not
  // a frame a sculptor sees, so it is left out of the frame times.
  double final_frame_wait_ms = 0;
  InputHubFigures hub;
  // The sculpting thread's waits as the last frame started (it then holds
  // the turn until everything is meshed, with no input left to wait).
  std::optional<InputHubFigures::TurnWaits> waits_while_playing;
  // CPU by thread as the session's frames ended, while the sculpting thread
  // still ran (stopped, it would count only under "ended"); none before.
  struct ThreadsAtEnd {
    std::vector<ThreadGroupTime> groups;
    int64_t at_ns = 0;
  };
  std::optional<ThreadsAtEnd> threads_at_end;
  // Why the threads a dab runs through are not real-time ("": they are).
  std::string realtime_note = "not started";
};

// Brick by brick, uniform bricks without decoding: --stats-every calls this
// on the frame's thread, where a dense copy of a 512^3 block would cost a
// noticeable frame.
int64_t solid_voxels(const core::Volume& v) {
  const int e = v.brick_edge();
  std::vector<uint8_t> voxels(static_cast<size_t>(e) * e * e);
  int64_t n = 0;
  for (int64_t i = 0; i < v.brick_count(); ++i) {
    const glm::ivec3 b = core::grid_position(i, v.brick_grid());
    const core::Box box = v.brick_box(b);
    const core::Brick& brick = v.brick(b);
    if (brick.is_uniform()) {
      n += brick.uniform_value() > 127 ? box.voxel_count() : 0;
      continue;
    }
    v.decode_brick(b, voxels);
    const glm::ivec3 size = box.size();  // the part inside the volume
    for (int z = 0; z < size.z; ++z)
      for (int y = 0; y < size.y; ++y)
        for (int x = 0; x < size.x; ++x)
          n += voxels[(static_cast<size_t>(z) * e + y) * e + x] > 127;
  }
  return n;
}

// Where each thread's time went since the window started: CPU seconds by
// thread name (the frame's thread is "sculpt", Mesa's rasterizers
// "llvmpipe"), and the wall time they shared.
nlohmann::ordered_json thread_figures(const RunFigures& f) {
  const RunFigures::ThreadsAtEnd now =
      f.threads_at_end ? *f.threads_at_end
                       : RunFigures::ThreadsAtEnd{thread_cpu_times(), hal::monotonic_ns()};
  nlohmann::ordered_json cpu = nlohmann::ordered_json::object();
  for (const ThreadGroupTime& g : now.groups)
    cpu[g.name] = {{"threads", g.threads}, {"cpu_s", g.cpu_s}};
  return {{"wall_s", static_cast<double>(now.at_ns - f.started_ns) * 1e-9},
          {"cpu_s", cpu},
          {"dab_path_realtime", f.realtime_note.empty()},
          {"dab_path_realtime_note", f.realtime_note}};
}

// The haptic loop's figures (DESIGN.md §5a), for --stats.
nlohmann::ordered_json haptic_figures(const HapticStation& h) {
  const HapticFigures f = h.figures();
  return {{"device", f.device},
          {"realtime", f.realtime},
          {"ticks", f.ticks},
          {"late_ticks", f.late_ticks},
          {"late_share",
           f.ticks > 0 ? static_cast<double>(f.late_ticks) / static_cast<double>(f.ticks) : 0.0},
          {"skipped_deadlines", f.skipped_deadlines},
          {"threads", f.threads},
          {"standby_rescues", f.standby_rescues},
          {"period_us_p50", f.period_p50_us},
          {"period_us_p99", f.period_p99_us},
          {"period_us_max", f.worst_period_us},
          {"watchdog_trips", f.watchdog_trips},
          {"device_faults", f.device_faults},
          {"records_dropped", f.records_dropped},
          {"max_force_n", f.max_force_n},
          {"loop_restarts", f.restarts},
          {"patch",
           {{"builds", f.patch.builds},
            {"refreshes", f.patch.refreshes},
            {"recentres", f.patch.recentres},
            {"publishes", f.patch.publishes},
            {"slowest_update_ms", f.patch.slowest_update_ms}}}};
}

nlohmann::ordered_json latency_figures(const LatencyStats& l) {
  return {{"count", l.count},
          {"p50", l.p50_us},
          {"p90", l.p90_us},
          {"p99", l.p99_us},
          {"max", l.max_us}};
}

// The slowest dabs to a first mesh, each split into report -> hand-over
// (the sculpting side) and hand-over -> mesh ready (the mesher).
nlohmann::ordered_json slowest_dab_figures(std::span<const InputStatistics::SlowDab> dabs) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const InputStatistics::SlowDab& d : dabs)
    list.push_back({{"first_mesh_ms", d.first_mesh_us * 1e-3},
                    {"handed_over_ms", d.handed_over_us * 1e-3},
                    {"meshing_ms", (d.first_mesh_us - d.handed_over_us) * 1e-3},
                    {"change", d.change}});
  return list;
}

Status write_stats(const std::string& path, const RunFigures& f, const StationController& c,
                   const HapticStation* haptics) {
  // What the program holds, apart from what the allocator keeps free: a
  // long run's resident memory can grow by fragmentation alone.
  const struct mallinfo2 heap = ::mallinfo2();
  auto at = [&](double q) { return f.frame_us.quantile_us(q) * 1e-3; };
  const double total = f.frames_total_ms;
  const double n = std::max<double>(1.0, static_cast<double>(f.frame_us.count()));
  nlohmann::ordered_json j = {
      {"frames", f.frame_us.count()},
      {"frames_drawn_unsteered", f.frames_drawn_unsteered},
      {"fps_mean", total > 0 ? 1000.0 * static_cast<double>(f.frame_us.count()) / total : 0.0},
      {"frame_ms_p50", at(0.5)},
      {"frame_ms_p90", at(0.9)},
      {"frame_ms_p99", at(0.99)},
      {"final_frame_wait_ms", f.final_frame_wait_ms},
      {"panel_drawn_anew", f.panel_rasters},
      {"brick_uploads", f.uploads},
      {"mesher",
       {{"changes", f.mesher.submits},
        {"bricks_submitted", f.mesher.bricks_submitted},
        {"bricks_coalesced", f.mesher.bricks_coalesced},
        {"bricks_unchanged", f.mesher.bricks_unchanged},
        {"pending_bricks_max", f.mesher.pending_bricks_max},
        {"coarse_first", f.mesher.coarse_first},
        {"update_page_faults", f.mesher.update_page_faults},
        {"coarse_updates", f.mesher.coarse_updates},
        {"refinements", f.mesher.refinements},
        {"refine_passes", f.mesher.refine_passes},
        {"refine_ms_max", f.mesher.refine_us.max_us() * 1e-3},
        {"updates", f.mesher.updates},
        {"bricks_meshed", f.mesher.bricks_meshed},
        {"bricks_reused", f.mesher.bricks_reused},
        {"bricks_given_by_the_sculptor", f.mesher.bricks_given},
        {"bricks_compared_where_changed", f.mesher.bricks_compared_where_changed},
        {"update_ms_p50", f.mesher.update_us.quantile_us(0.5) * 1e-3},
        {"update_ms_p99", f.mesher.update_us.quantile_us(0.99) * 1e-3},
        {"update_ms_max", f.mesher.update_us.max_us() * 1e-3},
        {"bricks_simplified", f.mesher.bricks_simplified},
        {"bricks_polished", f.mesher.bricks_polished},
        {"simplify_queue_max", f.mesher.simplify_queue_max},
        {"triangles_marched", f.mesher.triangles_marched},
        {"triangles_kept", f.mesher.triangles_kept},
        {"simplify_error_max_vox", f.mesher.simplify_error_max},
        {"simplify_ms_p99", f.mesher.simplify_us.quantile_us(0.99) * 1e-3}}},
      {"sculpting",
       {{"polls", f.hub.polls},
        {"polls_woken_by_a_report", f.hub.polls_on_reports},
        {"sculpt_ms", f.hub.sculpt_ms},
        {"waiting_for_the_frame_ms", f.hub.waits.sum_ms},
        {"waiting_for_the_frame_ms_max", f.hub.waits.max_ms},
        {"polls_waiting_over_1ms", f.hub.waits.over_1ms},
        {"events_held_for_offset_or_closing", f.hub.held_events},
        {"page_faults", f.hub.page_faults}}},
      {"mean_ms",
       {{"pointer_and_keys", f.input_ms / n},
        {"mesh", f.mesh_ms / n},
        {"upload", f.upload_ms / n},
        {"draw", f.draw_ms / n}}},
      {"threads", thread_figures(f)},
      {"undo_mib", static_cast<double>(c.loop().sculptor().history().memory_bytes()) / (1 << 20)},
      {"heap",
       {{"in_use_mib", static_cast<double>(heap.uordblks + heap.hblkhd) / (1 << 20)},
        {"free_mib", static_cast<double>(heap.fordblks) / (1 << 20)}}},
      {"dabs", c.loop().counters().dabs},
      {"strokes", c.loop().counters().strokes},
      {"rotation_cache", rotation_cache_figures(c.loop().rotation_cache_stats())},
      {"volume_hash", c.loop().volume().content_hash()},
      {"solid_voxels", solid_voxels(c.loop().volume())},
      {"triangles", f.triangles},
      {"dab_latency_us", latency_figures(c.session_latency())},
      {"full_detail_latency_us", latency_figures(c.full_detail_latency())},
      {"first_picture_latency_us", latency_figures(c.first_picture_latency())},
      {"slowest_dabs", slowest_dab_figures(c.slowest_dabs())},
      {"stand_ins",
       {{"dabs_stood_in", c.loop().counters().dabs_stood_in},
        {"dropped", c.stand_ins().dropped()}}},
      {"brush_previews",
       {{"shown", c.loop().counters().brush_previews},
        {"extended", c.loop().counters().brush_previews_extended}}}};
  if (haptics != nullptr) j["haptics"] = haptic_figures(*haptics);
  AtomicFileWriter w(path);
  if (!w.ok()) return w.error();
  w.write(j.dump(2) + "\n");
  return w.commit();
}

}  // namespace

int run_window(const WindowOptions& o) {
  // Freed memory stays mapped for the next dab, tool or mesh (memory_reuse.h):
  // up to a quarter of a gigabyte, about twice what a session holds.
  keep_freed_memory(size_t{256} << 20);
  core::start_pool_threads(kPoolThreadWarmHeapBytes);
  const std::vector<int> threads_before_gl = process_thread_ids();
  auto window = GlWindow::open(o.width, o.height, "Sculpt station", o.visible);
  if (!window) return fail(window.error());
  // The OpenGL driver's own threads (llvmpipe's rasterisers) draw the frames.
  const std::vector<int> drawing_threads = threads_started(threads_before_gl, process_thread_ids());
  GLFWwindow* w = (*window)->handle();
  glfwSwapInterval(o.vsync ? 1 : 0);
  auto renderer = gl::SceneRenderer::create();
  if (!renderer) return fail(renderer.error());
  {
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(w, &fb_w, &fb_h);
    (*renderer)->warm_up(std::max(fb_w, 1), std::max(fb_h, 1));
  }

  ControllerOptions co;
  co.loop.mesh = false;      // the window meshes what it draws (below), at its levels
  co.loop.clay_margin = 64;  // a slab of clay to carve, 128 voxels a side
  co.loop.undo_max_bytes = static_cast<size_t>(o.undo_mib) << 20;
  // Offset and closing take seconds on a big sculpture: computed on a
  // worker, the window draws and steers meanwhile (input_hub.cpp).
  co.loop.background_morphology = true;
  co.loop.hand_over_voxels = true;  // the mesher takes them (InputHub::poll)
  // A dab that adds the tool is drawn at once (app/dab_stand_ins.h).
  co.stand_ins = o.stand_ins;
  co.loop.pose.tracker = o.tracker;
  co.normalizer_config_path = hal::default_normalizer_config_path();
  StationController controller(co);
  controller.set_distance_normals(o.distance_normals);
  if (!o.project.empty()) {
    if (Status st = controller.open(o.project); !st) return fail(st.error());
  }

  // Devices: readers tap their raw reports into the recorder, which keeps
  // those not yet applied, so --record's recording has them from the first.
  auto config = hal::load_normalizer_config_or_defaults(co.normalizer_config_path);
  if (!config) return fail(config.error());
  hal::ReaderOptions reader_options;
  reader_options.on_raw = [&controller](const hal::RawEvent& e) { controller.raw_report(e); };
  reader_options.realtime_priority = kReaderRealtime;
  auto registry = std::make_unique<hal::DeviceRegistry>(hal::DeviceRegistry::default_backends(),
                                                        *config, reader_options);
  sim::SimBackend* sim_backend = nullptr;
  // A session that recorded a force device plays it too, unless another is given.
  std::unique_ptr<RecordedForceDevice> recorded_force;
  auto add_sim = [&](const std::string& file) -> Status {
    auto session = load_session(file);
    if (!session) return session.error();
    if (o.haptic.empty()) {
      auto force = RecordedForceDevice::from_session(*session, file, o.sim_speed);
      if (!force) return force.error();
      if (*force) recorded_force = std::make_unique<RecordedForceDevice>(std::move(**force));
    }
    // A session plays through the normaliser settings it was recorded with
    // (its header), as its replay does: the live result is then the same.
    auto recorded = hal::parse_normalizer_config(session->header.normalizer_config,
                                                 file + " (normaliser settings)");
    if (!recorded) return recorded.error();
    // A recording started on a sculpture plays onto it (session_start.h).
    auto started = restore_session_start(file, controller.loop());
    if (!started) return started.error();
    if (*started) {
      controller.frame_sculpture();
    }
    *config = *recorded;
    registry = std::make_unique<hal::DeviceRegistry>(std::vector<std::unique_ptr<hal::Backend>>{},
                                                     *config, reader_options);
    // Its clock starts once the opening surface is meshed (InputHub::run()).
    auto backend = std::make_unique<sim::SimBackend>(std::move(session).value(), file, o.sim_speed,
                                                     o.sim_loop, /*wait_for_start=*/true);
    sim_backend = backend.get();
    registry->add_backend(std::move(backend), /*first=*/true);
    auto id = registry->open_device("sim");
    if (!id) return id.error();
    return {};
  };
  if (o.device.rfind("sim:", 0) == 0) {
    if (Status st = add_sim(o.device.substr(4)); !st) return fail(st.error());
  } else if (o.device == "auto") {
    registry->scan();
    // With a force device the station is not idle: no demo then.
    if (registry->open_count() == 0 && o.project.empty() && o.haptic.empty()) {
      std::printf("no 3D mouse found: playing the demo session as a live device\n");
      if (Status st = add_sim(sim::bundled_session_path("demo")); !st) return fail(st.error());
    }
  } else {
    // A network tracker is opened only when named (tracker_backends.h).
    auto device = hal::add_named_tracker(*registry, o.device, o.listen);
    if (!device) return fail(device.error());
    auto id = registry->open_device(*device);
    if (!id) return fail(id.error());
  }
  // The surface drawn: each brick at the level its distance calls for,
  // crack-free where levels meet, meshed on the mesher's thread from a
  // mirror of the volume; the frame hands over what changed and draws
  // what is ready, never waiting for it.
  SurfaceMesher mesher(o.mesh_threads, o.simplify_error, kMesherWarmHeapBytes);
  // A force device: its loop ticks on its own thread (started with the hub);
  // the hub, made after it and so gone before it, runs its sculpting side
  // each poll.
  std::unique_ptr<HapticStation> haptics;
  std::optional<glm::vec3> haptic_origin_vox;  // where a recorded loop had the tool
  if (recorded_force) {
    HapticStationOptions ho;
    ho.contact = recorded_force->setup().contact;
    ho.loop = recorded_force->setup().loop;
    ho.drives_tool = false;  // the session's commands move the tool
    haptic_origin_vox = recorded_force->origin_tool_vox();
    haptics = std::make_unique<HapticStation>(std::move(recorded_force), ho);
  } else if (!o.haptic.empty()) {
    auto device = hal::open_force_device(o.haptic, {o.falcon_firmware});
    if (!device) return fail(device.error());
    HapticStationOptions ho;
    ho.contact.haptic.coupling.stiffness_n_per_mm = o.haptic_stiffness_n_per_mm;
    ho.contact.workspace_scale = o.workspace_scale;
    ho.contact.voxel_mm = o.voxel_mm;
    ho.thread.spin_ns = int64_t{o.haptic_spin_us} * 1000;
    ho.thread.standby = o.haptic_standby;
    ho.drives_tool = sim_backend == nullptr;  // a playing session owns the tool
    haptics = std::make_unique<HapticStation>(std::move(device).value(), ho);
  }
  // Devices are read and sculpted on the sculpting thread (input_hub.h);
  // each frame takes its turn with the controller for the mouse, the keys
  // and the panel, and draws without it.
  InputHub hub(controller, std::move(registry), sim_backend, hal::to_text(*config), mesher);
  hub.set_listener(haptics.get());
  if (!o.record.empty()) {
    if (Status st = controller.start_recording(o.record, hal::monotonic_ns()); !st)
      return fail(st.error());
  }
  // The sculpting thread touches a heap reserve first (memory_reuse.h), once
  // a recording has begun (it keeps the reports that arrive meanwhile) and
  // before a force device's loop starts: a session's first big stroke (the
  // demo's 66-voxel ball over 92 bricks) would otherwise fault in about
  // 17 MB, 35 ms, while the sculptor waits. 32 MiB was not enough: the
  // head's three balls' undo copies and the bricks handed to the mesher
  // used it up, and handing over the second ball's 64 bricks faulted 928
  // pages (7 ms). Touching 96 MiB takes 26-28 ms when the window opens
  // (32 MiB: 12 ms; where a fault costs 8 us, about 0.2 s). 160 MiB: the
  // stroke buffers for 512 bricks (50 MB) come out of it, and with 96 the
  // bust's tool changes and 110-voxel ball still faulted 6,000 pages.
  hub.prepare(size_t{160} << 20);
  // The mesher touched its own meanwhile, on the other core.
  mesher.wait_until_warm();

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // the panel's layout is not worth a file in the cwd
  ImGui::StyleColorsDark();
  // The window's sizes, focus and cursor as its events said (window_events.h);
  // watched first, so that ImGui's backend passes its events on.
  WindowEvents window_events;
  watch_window(w, &window_events);
  ImGui_ImplGlfw_InitForOpenGL(w, /*install_callbacks=*/true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
  PointerState pointer;
  // Where the cursor is now: a mouse that has not moved does not move the
  // tool (the first frame that steers may come after a session's device
  // has placed it; a jump to the cursor there would sculpt what the
  // recording did not).
  pointer.x = window_events.cursor_x;
  pointer.y = window_events.cursor_y;
  watch_scroll(w, &pointer);
  StationPanel panel(controller);
  panel.set_haptics(haptics.get());
  PanelLayer panel_layer;

  SurfaceSnapshot surface;
  SurfaceDelta unreported;  // meshes' ready times not yet given to the statistics
  // What the frame draws, as of the last frame that had the turn.
  struct Drawn {
    bool known = false;  // no frame has had the turn yet: nothing to draw
    gl::ToolDraw tool{};
    gl::SceneView view{};
    glm::vec3 block{0.0f};
    std::optional<HapticOverlay> haptics;
    std::optional<core::Box> tool_region;
  } drawn;
  RunFigures figures;
  FrameFigures frame_figures;
  int64_t last_frame = hal::monotonic_ns();
  int64_t last_stats = last_frame;
  figures.started_ns = last_frame;
  if (haptics) {
    // With the hub, so the loop's records are taken from its first tick.
    // The tool starts resting over the sculpture's top, at its middle: a
    // device at the centre of its workspace then holds the tool just above
    // the clay, wherever the pose was left.
    glm::vec3 start = controller.loop().pose().position;
    if (const auto bounds = core::material_bounds(controller.loop().volume())) {
      const glm::vec3 lo(bounds->lo), hi(bounds->hi);
      start = glm::vec3(0.5f * (lo.x + hi.x), hi.y + controller.loop().tool_size() * 0.5f + 4.0f,
                        0.5f * (lo.z + hi.z));
    }
    haptics->start(haptic_origin_vox.value_or(start), controller.loop().tool_size() * 0.5f);
    if (const HapticFigures hf = haptics->figures(); !hf.realtime)
      std::printf("%s\n", hf.realtime_note.c_str());
  }
  hub.start();
  // The dab's path goes first, and the OpenGL driver's and the frame's
  // threads go after it (below). Measured on the demo, six pairs against
  // the same build without it (drawing at niceness 5 in both): dab latency
  // p99 7.1-10.1 against 8.7-14.2 ms, max 13.3-19.8 against 15.1-26.2 ms;
  // frames p99 about 1.5 ms longer, as a big dab now holds both cores
  // while it is meshed.
  figures.realtime_note = make_dab_path_realtime();
  if (!figures.realtime_note.empty())
    std::printf(
        "sculpting and meshing: no real-time priority (%s); a big dab shares the cores "
        "with drawing (give the user rtprio in /etc/security/limits.conf)\n",
        figures.realtime_note.c_str());
  // Drawing yields the cores to sculpting and meshing (thread_priority.h):
  // the frames drawn while a big dab meshes show the old surface anyway.
  // Made nicer only now, so the threads started above (sculpting, meshing,
  // the force loop) keep their niceness; those the frame starts later (a
  // tool's stand-in mesh, an autosave, an offset from the panel) inherit it,
  // and none of them is more urgent than a frame. Measured on the demo, at
  // 5 against none: the first ball's meshing 14.8, 20.7, 14.9 against 17.0,
  // 16.0, 17.2 ms beside llvmpipe, dab latency p99 8.4, 8.8, 8.1 against
  // 12.2, 11.5, 11.8 ms, frames as fast (three runs each); 12 did no better.
  {
    std::vector<int> drawing = drawing_threads;
    drawing.push_back(this_thread_id());
    make_threads_nicer(drawing, kDrawingNice);
  }
  bool played_out = false;  // the last frame of --until-replayed is drawn
  // The mesher's newest meshes into the frame's snapshot, with their ready
  // times (each dab's latency ends there; the statistics take them with
  // the turn).
  auto take_meshes = [&] {
    if (auto delta = mesher.take()) {
      unreported.readiness.insert(unreported.readiness.end(), delta->readiness.begin(),
                                  delta->readiness.end());
      surface.apply(std::move(*delta));
    }
  };
  for (int frame = 0;
       !glfwWindowShouldClose(w) && (o.frames <= 0 || frame < o.frames) && !played_out; ++frame) {
    glfwPollEvents();
    const int64_t now = hal::monotonic_ns();
    // The sculpting thread plays a sim device's session at its own pace, so
    // it can end before a slow frame (a sanitizer's, a loaded machine's) has
    // shown anything: the frame after it shows the end, then the window goes.
    // Without a session, a simulated arm's script ends the run by unplugging it.
    played_out = o.exit_when_replayed &&
                 (sim_backend != nullptr ? hub.replay_done() : haptics && haptics->device_gone());
    const bool final_frame = played_out || (o.frames > 0 && frame == o.frames - 1);
    // The sculpting thread holds the turn while it sculpts, tens of
    // milliseconds for a big tool's first placement: a frame that finds it
    // busy does not wait but draws what it has (the meshes made meanwhile
    // included), and the next frame that gets the turn steers (mouse, keys,
    // levels, panel). The last frame waits: it shows everything.
    int64_t final_wait_ns = 0;
    // The meshes made since the last frame go into the frame's own snapshot
    // before the turn: the mesher and the snapshot need nothing the turn
    // guards, and taking in a new block's opening surface took up to 9.9 ms
    // (the bust's, at its second frame) that the sculpting thread could
    // have waited for.
    const int64_t t_take = hal::monotonic_ns();
    take_meshes();
    const int64_t t_turn = hal::monotonic_ns();
    const int64_t take_ns = t_turn - t_take;
    std::unique_lock turn = hub.frame_turn(final_frame);
    if (final_frame) final_wait_ns += hal::monotonic_ns() - t_turn;
    const bool steering = turn.owns_lock();
    if (final_frame) figures.waits_while_playing = hub.figures().waits;
    if (!steering) ++figures.frames_drawn_unsteered;
    // From the window's events: asking the X server is a round trip, up to
    // 12 ms under Xvfb beside llvmpipe, which the turn would make the
    // sculpting thread wait for.
    const int fb_w = window_events.framebuffer_w, fb_h = window_events.framebuffer_h;
    const float aspect =
        static_cast<float>(std::max(fb_w, 1)) / static_cast<float>(std::max(fb_h, 1));
    const ImGuiIO& io = ImGui::GetIO();
    if (steering) {
      steer_with_pointer_and_keys(w, window_events, aspect, now, last_frame, pointer, controller,
                                  haptics.get());
      // The level each brick is drawn at, for the mesher, from the view.
      const OrbitCamera& camera = controller.camera();
      const core::Volume& volume = controller.loop().volume();
      LodPolicy policy = controller.lod().policy();
      policy.max_level = std::min(kMaxDrawnLevel, volume.levels());
      if (frame == 0 && o.lod >= 0) policy.fixed_level = o.lod;
      controller.lod().set_policy(policy);
      hub.set_levels(
          controller.lod().select(volume.brick_grid(), volume.brick_edge(), camera.eye(),
                                  OrbitCamera::focal_length_px(static_cast<float>(fb_h))));
    }
    const int64_t t_mesh = hal::monotonic_ns();
    figures.input_ms += static_cast<double>(t_mesh - now - take_ns) * 1e-6;
    // The last frame (and so its picture) shows everything sculpted before
    // it, and every brick shaded as it asks.
    const bool picture_frame = !o.screenshot.empty() && final_frame;
    int64_t mesher_wait_ns = 0;
    if (final_frame) {
      hub.poll_now();
      mesher.wait_until_meshed();
      mesher_wait_ns = hal::monotonic_ns() - t_mesh;
      final_wait_ns += mesher_wait_ns;
    }
    if (final_frame) take_meshes();  // everything, now that all is meshed
    // Dabs not meshed yet that a stand-in shows (its own lock, not the turn).
    const std::vector<DabStandIn> stand_ins = controller.stand_ins().showing(surface.change());
    // A changed tool and its version, outlined after the turn.
    std::optional<std::pair<std::shared_ptr<const core::Tool>, uint64_t>> changed_tool;
    const int64_t t_upload = hal::monotonic_ns();
    figures.mesh_ms += static_cast<double>(t_upload - t_mesh - mesher_wait_ns + take_ns) * 1e-6;
    if (steering) {
      controller.surface_ready(unreported);
      unreported.readiness.clear();
      (*renderer)->set_distance_normals(controller.distance_normals());
      // A changed tool is outlined after the turn (a ring's or a cube's
      // outline is marched and simplified: 2.7 ms the sculpting thread
      // waited for on the demo), from the loop's shared, unchanging copy.
      if (const uint64_t version = controller.loop().tool_version();
          version != (*renderer)->tool_version())
        changed_tool.emplace(controller.loop().shared_tool(), version);
      const SheetEditor& sheet = controller.loop().sheet();
      (*renderer)->set_sheet(sheet.mesh(), sheet.version(),
                             controller.loop().settings().sheet_editing);
      const hal::ToolPose& pose = controller.loop().pose();
      drawn.tool = {true, pose.position, pose.orientation, controller.loop().settings().mode,
                    controller.loop().pressed()};
      const OrbitCamera& camera = controller.camera();
      drawn.view = {camera.view(), camera.projection(aspect), camera.eye(), fb_w, fb_h};
      drawn.block = glm::vec3(controller.loop().volume().dims());
      drawn.tool_region = controller.tool_region();
      drawn.known = true;
      if (haptics) {
        HapticOverlayInput overlay;
        overlay.device_vox = haptics->contact().device_vox;
        overlay.proxy_vox = haptics->contact().proxy_vox;
        overlay.radius_vox = controller.loop().tool_size() * 0.5f;
        overlay.force_n = haptics->tick().force_n;
        drawn.haptics = haptic_overlay(overlay);
      }
    }
    // The meshes are the frame's own (the snapshot's), uploaded after the
    // turn: 84 bricks' took 1.3 ms the sculpting thread waited for. Their
    // re-shading with distance normals reads the volume, so it is done
    // under the turn, for the bricks uploaded by earlier frames, or for a
    // picture every brick after its upload.
    gl::SurfaceSync sync;
    if (picture_frame) {
      sync = (*renderer)->sync_surface(&controller.loop().volume(), surface, /*whole=*/true);
    } else if (steering) {
      (*renderer)->reshade(controller.loop().volume());
    }
    if (steering) turn.unlock();
    if (!picture_frame) sync = (*renderer)->upload_surface(surface);
    // The stand-ins' tool mesh, uploaded when it changed (the board has its own lock).
    (*renderer)->set_stand_in_tool(controller.stand_ins().tool());
    if (changed_tool) (*renderer)->set_tool(*changed_tool->first, changed_tool->second);

    // Draw, without holding up the sculpting.
    const int64_t t_draw = hal::monotonic_ns();
    figures.upload_ms += static_cast<double>(t_draw - t_upload) * 1e-6;
    if (drawn.known) {
      (*renderer)->draw(drawn.view, drawn.tool, drawn.block, stand_ins);
      if (drawn.haptics) (*renderer)->draw_haptics(drawn.view, *drawn.haptics);
      if (drawn.tool_region) {
        // Voxel centres are at integers: the region's voxels span lo - 0.5 to hi - 0.5.
        (*renderer)->draw_box(drawn.view, glm::vec3(drawn.tool_region->lo) - 0.5f,
                              glm::vec3(drawn.tool_region->hi) - 0.5f, {0.45f, 0.95f, 0.55f, 1.0f});
      }
    }
    if (picture_frame) {
      RgbImage shot{fb_w, fb_h, {}};
      read_pixels(fb_w, fb_h, shot.rgb);
      if (Status st = write_png(o.screenshot, shot); !st) return fail(st.error());
    }
    // The panel reads and sets the controller: drawn with the turn, else
    // the last frame's panel is drawn again. The OpenGL backend's frame
    // start reads nothing of it: the first one builds the font atlas and
    // compiles the backend's shaders, 1.4 ms the sculpting thread waited for.
    ImGui_ImplOpenGL3_NewFrame();
    const int64_t t_panel_turn = hal::monotonic_ns();
    turn = hub.frame_turn(final_frame);
    if (final_frame) final_wait_ns += hal::monotonic_ns() - t_panel_turn;
    const bool panel_turn = turn.owns_lock();
    if (panel_turn) {
      begin_panel_frame(w, window_events);  // from the window's events: no round trip
      ImGui::NewFrame();
      frame_figures.triangles = sync.triangles;
      frame_figures.uploaded = sync.uploaded;
      panel.draw(frame_figures, now);
      if (!io.WantCaptureKeyboard) {
        for (int k = GLFW_KEY_SPACE; k <= GLFW_KEY_LAST; ++k) {
          if (!ImGui::IsKeyPressed(k, false)) continue;
          const int mods = (io.KeyCtrl ? GLFW_MOD_CONTROL : 0) | (io.KeyShift ? GLFW_MOD_SHIFT : 0);
          if (haptics && k == GLFW_KEY_K && mods == 0) {
            haptics->enabled() ? haptics->drop() : haptics->enable();
            continue;
          }
          const std::optional<Action> action = shortcut(k, mods);
          // A new block cannot be undone: the panel asks first.
          if (action == Action::kNewBlock) {
            panel.ask_new_block();
          } else if (action) {
            controller.perform(*action, now);
          }
        }
      }
      if (!o.stats.empty() && o.stats_every_s > 0 &&
          now - last_stats >= static_cast<int64_t>(o.stats_every_s * 1e9)) {
        figures.mesher = mesher.counters();
        figures.hub = hub.figures();
        if (Status st = write_stats(o.stats, figures, controller, haptics.get()); !st)
          return fail(st.error());
        last_stats = now;
      }
      turn.unlock();
      ImGui::Render();
    }
    // After NewFrame() a Render() follows: the draw data are this frame's, or
    // the last one's again.
    if (ImDrawData* panel_draw = ImGui::GetDrawData(); panel_draw != nullptr)
      panel_layer.draw(*panel_draw, panel.textures_version());
    figures.panel_rasters = panel_layer.rasters();
    glfwSwapBuffers(w);
    figures.draw_ms += static_cast<double>(hal::monotonic_ns() - t_draw) * 1e-6;

    const int64_t end = hal::monotonic_ns();
    const double ms = static_cast<double>(end - now - final_wait_ns) * 1e-6;
    figures.final_frame_wait_ms += static_cast<double>(final_wait_ns) * 1e-6;
    figures.frame_us.add(ms * 1e3);
    figures.frames_total_ms += ms;
    figures.uploads += sync.uploaded;
    figures.triangles = sync.triangles;
    if (std::unique_lock lod_turn(hub.mutex(), std::try_to_lock); lod_turn.owns_lock())
      controller.lod().frame_done(ms);  // a frame's time left out is no loss to its average
    frame_figures.frame_ms = 0.9 * frame_figures.frame_ms + 0.1 * ms;
    frame_figures.fps = frame_figures.frame_ms > 0 ? 1000.0 / frame_figures.frame_ms : 0;
    last_frame = now;
  }

  figures.threads_at_end = RunFigures::ThreadsAtEnd{thread_cpu_times(), hal::monotonic_ns()};
  // What the devices said last is sculpted, and the dabs of the last
  // frames count in the latency figures too.
  hub.stop();
  std::lock_guard last_turn(hub.mutex());  // no other thread now: kept for the rule
  hub.poll_now(/*land=*/true);
  if (haptics) haptics->stop();  // zero force; its figures are final
  mesher.wait_until_meshed();
  if (auto delta = mesher.take()) controller.surface_ready(*delta);
  figures.mesher = mesher.counters();
  figures.hub = hub.figures();
  if (figures.waits_while_playing) figures.hub.waits = *figures.waits_while_playing;

  watch_scroll(w, nullptr);
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  if (controller.recording()) {
    if (Status st = controller.stop_recording(); !st) return fail(st.error());
    std::printf("%s\n", controller.status().c_str());
  }
  // A recording asked for on the command line that stopped by itself is
  // not a success: what was written before the failure stays readable.
  if (!o.record.empty() && !controller.recording_error().empty())
    return fail(Error("recording stopped early: " + controller.recording_error()));
  controller.finish_autosave();
  if (!o.stats.empty()) {
    if (Status st = write_stats(o.stats, figures, controller, haptics.get()); !st)
      return fail(st.error());
  }
  return 0;
}

}  // namespace sculpt::station
