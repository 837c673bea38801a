// The window and the GL renderer, run as a user runs them, on a real X
// server: the test's own display, or one started by xvfb-run (Mesa's
// software OpenGL in CI). Skipped only when neither exists.

#include <stb_image.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <utility>

#include <gtest/gtest.h>
#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>

#include "../cli/run_sculpt.h"
#include "../replay_fast.h"
#include "picture_difference.h"
#include "sanitized.h"
#include "scratch_dir.h"
#include "sculpt/core/files/volume_file.h"
#include "sculpt/core/mesh/mesh.h"
#include "sculpt/sim/session/session_file.h"
#include "sculpt/sim/synth/bundled_sessions.h"
#include "sculpt/station/app/session_loading.h"
#include "sculpt/station/app/session_replay.h"
#include "sculpt/station/haptics/haptic_replay.h"
#include "sculpt/station/project/project_file.h"
#include "sculpt/station/settings/command_codec.h"
#include "sculpt/station/view/orbit_camera.h"
#include "sculpt/station/window/gl_snapshot.h"

namespace sculpt::station::test {
namespace {

using ::sculpt::test::replay_fast;

// `sculpt ARGS` with a display: the current one, else a private Xvfb, run
// in `dir` (the window autosaves its default project there).
// Under AddressSanitizer the child runs without leak detection: Mesa's
// driver is unloaded at exit, so its process-lifetime allocations show as
// leaks from an unknown module that no suppression can name. (The station's
// own code is leak-checked in-process by the GL-free tests.)
std::optional<CommandResult> run_with_display(const std::string& args,
                                              const std::filesystem::path& dir) {
  std::string launcher;
  if (!display_available()) {
    if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) return std::nullopt;
    // xvfb-run starts an X server just for this command (-a: a free number).
    // Its X authority file lives in `dir` (-f): left to itself, xvfb-run
    // makes a temporary directory and exits 5, whatever the command did,
    // when removing it fails, which it did once under parallel ctest.
    launcher = "xvfb-run -a -f '" + (dir / "xvfb-auth").string() + "' -s '-screen 0 1280x1024x24' ";
  }
  const std::string sculpt = std::string(SCULPT_BINARY_DIR) + "/bin/sculpt";
  const auto err =
      std::filesystem::temp_directory_path() / ("sculpt_xvfb_err_" + std::to_string(::getpid()));
  const std::string command =
      "cd '" + dir.string() +
      "' && ASAN_OPTIONS=\"${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0\" " + launcher + sculpt +
      " " + args + " 2>" + err.string();
  CommandResult r;
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return std::nullopt;
  char buffer[4096];
  for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;)
    r.out.append(buffer, n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = read_text(err);
  std::filesystem::remove(err);
  return r;
}

struct Picture {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;
  // Clay-coloured pixels, lit or in shadow (warm: red above blue); the
  // background, grid and bounds are grey-blue (blue above red).
  bool clay(int x, int y) const {
    const uint8_t* p = &rgb[(static_cast<size_t>(y) * width + x) * 3];
    return p[0] > p[2] + 6;
  }
};

Picture read_png(const std::string& path) {
  Picture p;
  int channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &p.width, &p.height, &channels, 3);
  if (data == nullptr) return p;
  p.rgb.assign(data, data + static_cast<size_t>(p.width) * p.height * 3);
  stbi_image_free(data);
  return p;
}

struct PixelBox {
  int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
  int64_t count = 0;
  void add(int x, int y) {
    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
    ++count;
  }
  int64_t area() const { return int64_t{x1 - x0 + 1} * (y1 - y0 + 1); }
};

TEST(StationWindow, ReplayRendersTheDemoThroughAnInvisibleGlWindow) {
  sculpt::test::ScratchDir dir;
  const std::string demo = sim::bundled_session_path("demo");
  auto r = run_with_display("replay " + demo + " --fast --renderer gl --png " +
                                dir.file("demo.png") + " --stats " + dir.file("s.json"),
                            dir.path());
  if (!r) GTEST_SKIP() << "no display and no xvfb-run";
  ASSERT_EQ(r->exit_code, 0) << r->err;
  const auto stats = nlohmann::json::parse(read_text(dir.file("s.json")));
  EXPECT_EQ(stats["renderer"], "gl");

  // Where the demo's surface must appear: its vertices projected with the
  // camera the snapshot uses.
  auto session = load_session(demo);
  ASSERT_TRUE(session.ok());
  StationLoop loop(StationLoop::Options{});
  ASSERT_TRUE(replay_fast(*session, "demo", loop).ok());
  const core::Mesh mesh = loop.mesh().welded_mesh();
  // Framed on the sculpture, not its block.
  OrbitCamera camera;
  const core::MeshBounds bounds = core::mesh_bounds(mesh);
  camera.frame(bounds.lo, bounds.hi);
  const glm::mat4 vp = camera.projection(1.0f) * camera.view();
  PixelBox expected;
  for (const glm::vec3& v : mesh.positions) {
    const glm::vec4 c = vp * glm::vec4(v, 1.0f);
    expected.add(static_cast<int>((c.x / c.w * 0.5f + 0.5f) * 800.0f),
                 static_cast<int>((0.5f - c.y / c.w * 0.5f) * 800.0f));
  }

  const Picture p = read_png(dir.file("demo.png"));
  ASSERT_EQ(p.width, 800);
  ASSERT_EQ(p.height, 800);
  PixelBox seen;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x)
      if (p.clay(x, y)) seen.add(x, y);
  // Not blank, the silhouette where the geometry says, and a solid head
  // (a round shape fills about pi/4 of its bounding box).
  ASSERT_GT(seen.count, 10000);
  EXPECT_NEAR(seen.x0, expected.x0, 3);
  EXPECT_NEAR(seen.x1, expected.x1, 3);
  EXPECT_NEAR(seen.y0, expected.y0, 3);
  EXPECT_NEAR(seen.y1, expected.y1, 3);
  const double fill = static_cast<double>(seen.count) / static_cast<double>(expected.area());
  EXPECT_GT(fill, 0.55);
  EXPECT_LT(fill, 0.95);
}

TEST(StationWindow, RunsTheLiveLoopOnASimDeviceAndTakesAScreenshot) {
  sculpt::test::ScratchDir dir;
  auto r = run_with_display("run --device sim:" + sim::bundled_session_path("short") +
                                " --speed 4 --until-replayed --hidden --no-vsync --lod 0 --stats " +
                                dir.file("s.json") + " --record " + dir.file("again.scs"),
                            dir.path());
  if (!r) GTEST_SKIP() << "no display and no xvfb-run";
  ASSERT_EQ(r->exit_code, 0) << r->err;
  const auto stats = nlohmann::json::parse(read_text(dir.file("s.json")));
  // How many frames the session took depends on the machine's speed (under
  // a sanitizer on a loaded machine a frame can take seconds): only that the
  // window drew.
  EXPECT_GE(stats["frames"].get<int>(), 1);
  EXPECT_GT(stats["dabs"].get<int>(), 10);
  EXPECT_EQ(stats["dab_latency_us"]["count"], stats["dabs"]);
  // The slowest dabs are named, slowest first, the slowest the maximum, each
  // split into its sculpting and its meshing.
  const auto& slowest = stats["slowest_dabs"];
  ASSERT_FALSE(slowest.empty());
  EXPECT_LE(slowest.size(), 8u);
  EXPECT_NEAR(slowest[0]["first_mesh_ms"].get<double>() * 1e3,
              stats["dab_latency_us"]["max"].get<double>(), 1.0);
  for (size_t i = 0; i < slowest.size(); ++i) {
    const auto& d = slowest[i];
    EXPECT_NEAR(d["handed_over_ms"].get<double>() + d["meshing_ms"].get<double>(),
                d["first_mesh_ms"].get<double>(), 1e-6);
    EXPECT_GE(d["handed_over_ms"].get<double>(), 0.0);
    if (i > 0) {
      EXPECT_LE(d["first_mesh_ms"].get<double>(), slowest[i - 1]["first_mesh_ms"].get<double>());
    }
  }
  EXPECT_GT(stats["triangles"].get<int>(), 1000);
  // The sculpting thread's waits for the frame's turn: their sum, the
  // longest, and how many polls waited over a millisecond.
  const auto& sculpting = stats["sculpting"];
  EXPECT_LE(sculpting["waiting_for_the_frame_ms_max"].get<double>(),
            sculpting["waiting_for_the_frame_ms"].get<double>());
  EXPECT_LE(sculpting["polls_waiting_over_1ms"].get<int64_t>(), sculpting["polls"].get<int64_t>());
  EXPECT_GE(sculpting["waiting_for_the_frame_ms"].get<double>(),
            1.0 * sculpting["polls_waiting_over_1ms"].get<double>());
  // Its heap warmed (memory_reuse.h), the sculpting thread takes next to no
  // page faults while it sculpts (8 here; without the reserve, a fault per
  // fresh page its strokes touch). A sanitizer's allocator keeps nothing.
  const auto page_faults = sculpting.at("page_faults").get<int64_t>();  // reported anyway
  if (!sculpt::test::kSanitized) {
    EXPECT_LT(page_faults, 100);
  }
  // The strokes' bricks reach the mesher with their voxels: not decoded again.
  EXPECT_GT(stats["mesher"]["bricks_given_by_the_sculptor"].get<int64_t>(), 0) << stats.dump();
  EXPECT_LE(stats["mesher"]["bricks_given_by_the_sculptor"].get<int64_t>(),
            stats["mesher"]["bricks_submitted"].get<int64_t>());
  // And with where they changed since the mirror's version: compared only there.
  EXPECT_GT(stats["mesher"]["bricks_compared_where_changed"].get<int64_t>(), 0) << stats.dump();
  EXPECT_LE(stats["mesher"]["bricks_compared_where_changed"].get<int64_t>(),
            stats["mesher"]["bricks_given_by_the_sculptor"].get<int64_t>());
  // Where each thread's time went, the sculpting thread's and the mesher's
  // included (taken as the frames end, while they still run).
  EXPECT_TRUE(stats["threads"]["cpu_s"].contains("sculpting")) << stats["threads"].dump();
  EXPECT_TRUE(stats["threads"]["cpu_s"].contains("mesher")) << stats["threads"].dump();
  // What the window recorded replays to what the window sculpted, bit for
  // bit, however the frames fell.
  auto again = load_session(dir.file("again.scs"));
  ASSERT_TRUE(again.ok()) << again.error().message();
  StationLoop loop(StationLoop::Options{});
  ASSERT_TRUE(replay_fast(*again, "again", loop).ok());
  // What the window said, for when the recording does not replay to it.
  const std::string said = "window stdout: " + r->out + "\nwindow stderr: " + r->err +
                           "\nrecording: " + std::to_string(again->records.size()) + " records";
  EXPECT_EQ(loop.counters().strokes, stats["strokes"].get<int64_t>()) << said;
  EXPECT_EQ(loop.counters().dabs, stats["dabs"].get<int64_t>()) << said;
  EXPECT_EQ(loop.volume().content_hash(), stats["volume_hash"].get<uint64_t>()) << said;
  EXPECT_GT(stats["solid_voxels"].get<int64_t>(), 500);

  // A project opened in the window and drawn, shaded with the distance
  // field's normals.
  auto saved = run_sculpt("replay " + sim::bundled_session_path("short") + " --fast --project " +
                          dir.file("short.sculpt"));
  ASSERT_EQ(saved.exit_code, 0) << saved.err;
  r = run_with_display("run --open " + dir.file("short.sculpt") +
                           " --frames 5 --hidden --normals distance --screenshot " +
                           dir.file("shot.png"),
                       dir.path());
  ASSERT_EQ(r->exit_code, 0) << r->err;
  const Picture p = read_png(dir.file("shot.png"));
  ASSERT_GT(p.width, 0);
  int64_t clay = 0;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x)
      clay += p.clay(x, y);
  EXPECT_GT(clay, 500);
}

// The live path (reader thread, ring, every sample in order, commands among
// the reports) sculpts exactly what the deterministic replay does: the demo,
// and the sheet session (the NURBS sheet drawn, dragged by the device and
// added to the material).
TEST(StationWindow, PlayingTheDemoLiveSculptsWhatItsReplaySculpts) {
  // Meshing runs on its own threads, at its own pace: whatever their number,
  // the sculpture is the replay's.
  const std::pair<const char*, int> runs[] = {{"demo", 1}, {"demo", 2}, {"sheet", 0}};
  for (const auto& [name, mesh_threads] : runs) {
    sculpt::test::ScratchDir dir;
    auto r =
        run_with_display("run --device sim:" + sim::bundled_session_path(name) +
                             " --speed 4 --until-replayed --hidden --no-vsync --mesh-threads " +
                             std::to_string(mesh_threads) + " --stats " + dir.file("s.json"),
                         dir.path());
    if (!r) GTEST_SKIP() << "no display and no xvfb-run";
    ASSERT_EQ(r->exit_code, 0) << r->err;
    const auto stats = nlohmann::json::parse(read_text(dir.file("s.json")));
    auto session = load_session(sim::bundled_session_path(name));
    ASSERT_TRUE(session.ok());
    StationLoop loop(StationLoop::Options{});
    ASSERT_TRUE(replay_fast(*session, name, loop).ok());
    EXPECT_EQ(stats["dabs"].get<int64_t>(), loop.counters().dabs) << name;
    EXPECT_EQ(stats["volume_hash"].get<uint64_t>(), loop.volume().content_hash())
        << name << " " << mesh_threads;
    EXPECT_GT(stats["triangles"].get<int64_t>(), 1000) << name;
  }
}

// Tools in the window (issue 23): a session whose device gives a tool whole
// (tool_voxels, then tool_scale) plays live; the window's own recording
// carries the tool's voxels bit for bit and replays to what it sculpted;
// the tool library's pictures are rendered and uploaded from the tools
// folder without trouble.
TEST(StationWindow, AToolGivenWholePlaysLiveAsItReplaysWithTheLibraryShown) {
  sculpt::test::ScratchDir dir;
  std::filesystem::create_directories(dir.path() / "tools");
  ASSERT_TRUE(
      core::write_tool_file(dir.path() / "tools" / "ball.nrrd", core::make_sphere_tool(6.0f)).ok());
  ASSERT_TRUE(
      core::write_tool_file(dir.path() / "tools" / "ring.nrrd", core::make_ring_tool(6.0f, 2.0f))
          .ok());
  auto session = load_session(sim::bundled_session_path("short"));
  ASSERT_TRUE(session.ok());
  // Before the device's first report: the whole stroke sculpts with the cone.
  auto first = std::find_if(
      session->records.begin(), session->records.end(),
      [](const sim::SessionRecord& r) { return r.kind == sim::SessionRecord::Kind::kEvent; });
  ASSERT_NE(first, session->records.end());
  const int64_t t = first->t_ns();
  sim::Command give{sim::CommandKind::kToolVoxels};
  give.voxels =
      std::make_shared<const sim::ToolVoxels>(tool_voxels_of(core::make_cone_tool(6.0f, 10.0f)));
  const sim::Command scale{sim::CommandKind::kToolScale, 0, {1.5f}};
  session->records.insert(first,
                          {sim::SessionRecord::of(t, give), sim::SessionRecord::of(t, scale)});
  ASSERT_TRUE(sim::write_session_file(dir.path() / "tool.scs", *session).ok());

  auto r = run_with_display("run --device sim:" + dir.file("tool.scs") +
                                " --speed 4 --until-replayed --hidden --no-vsync --stats " +
                                dir.file("s.json") + " --record " + dir.file("again.scs"),
                            dir.path());
  if (!r) GTEST_SKIP() << "no display and no xvfb-run";
  ASSERT_EQ(r->exit_code, 0) << r->err;
  const auto stats = nlohmann::json::parse(read_text(dir.file("s.json")));
  EXPECT_GT(stats["dabs"].get<int64_t>(), 10);
  // The window sculpted what the session's replay does, its unplug and
  // re-plug included; it recorded the tool's voxels as the device gave them,
  // and its recording replays to what it sculpted.
  StationLoop from_session(StationLoop::Options{});
  ASSERT_TRUE(replay_fast(*session, "tool.scs", from_session).ok());
  EXPECT_EQ(from_session.volume().content_hash(), stats["volume_hash"].get<uint64_t>());
  EXPECT_EQ(from_session.counters().disconnects, 1);
  auto again = load_session(dir.file("again.scs"));
  ASSERT_TRUE(again.ok()) << again.error().message();
  int given = 0, scaled = 0;
  for (const sim::SessionRecord& rec : again->records) {
    if (rec.kind != sim::SessionRecord::Kind::kCommand) continue;
    if (rec.command.kind == sim::CommandKind::kToolVoxels) {
      ++given;
      EXPECT_EQ(rec.command, give);
    }
    if (rec.command.kind == sim::CommandKind::kToolScale) {
      ++scaled;
      EXPECT_EQ(rec.command, scale);
    }
  }
  EXPECT_EQ(given, 1);
  EXPECT_EQ(scaled, 1);
  StationLoop from_window(StationLoop::Options{});
  ASSERT_TRUE(replay_fast(*again, "again.scs", from_window).ok());
  EXPECT_EQ(from_window.volume().content_hash(), stats["volume_hash"].get<uint64_t>());
}

using ::sculpt::test::PictureDifference;

PictureDifference difference(const Picture& a, const Picture& b) {
  return ::sculpt::test::picture_difference(a.rgb, b.rgb);
}

// The demo sculpture saved as a project, to open in the window.
std::string demo_project(const sculpt::test::ScratchDir& dir) {
  auto saved = run_sculpt("replay " + sim::bundled_session_path("demo") + " --fast --project " +
                          dir.file("demo.sculpt"));
  EXPECT_EQ(saved.exit_code, 0) << saved.err;
  return dir.file("demo.sculpt");
}

struct Shot {
  Picture picture;
  int64_t triangles = 0;
};

// The window's picture of `project` after a few frames with `options`;
// nothing when there is no display to open it on.
std::optional<Shot> shoot(const sculpt::test::ScratchDir& dir, const std::string& project,
                          const std::string& options) {
  const std::string shot = dir.file("shot.png");
  auto r = run_with_display("run --open " + project + " --frames 3 --hidden " + options +
                                " --screenshot " + shot + " --stats " + dir.file("s.json"),
                            dir.path());
  if (!r) return std::nullopt;
  EXPECT_EQ(r->exit_code, 0) << r->err;
  return Shot{read_png(shot),
              nlohmann::json::parse(read_text(dir.file("s.json")))["triangles"].get<int64_t>()};
}

// The demo project seen zoomed out to its whole block (the project opens
// on its sculpture framed).
std::string zoomed_out_demo_project(const sculpt::test::ScratchDir& dir) {
  auto project = load_project(demo_project(dir));
  if (!project.ok()) {
    ADD_FAILURE() << project.error().message();
    return {};
  }
  OrbitCamera whole_block;
  whole_block.frame(glm::vec3(0.0f), glm::vec3(project->volume->dims()));
  const std::string path = dir.file("demo_zoomed_out.sculpt");
  EXPECT_TRUE(save_project(path, *project->volume, project->settings,
                           project->custom_tool ? &*project->custom_tool : nullptr,
                           project_view(whole_block))
                  .ok());
  return path;
}

// What the sculptor sees at automatic level of detail is the full-detail
// picture to within a pixel's error, whichever normals shade it: a small
// window, zoomed out, makes the demo's far bricks coarse (a quarter of the
// triangles), and the picture must not show it (no facet, seam or shading
// step).
TEST(StationWindow, AutomaticLevelOfDetailLooksLikeFullDetail) {
  sculpt::test::ScratchDir dir;
  const std::string project = zoomed_out_demo_project(dir);
  ASSERT_FALSE(project.empty());
  for (const char* normals : {"distance", "density"}) {
    const std::string options = std::string("--size 256x160 --normals ") + normals;
    const auto automatic = shoot(dir, project, options);
    const auto full = shoot(dir, project, options + " --lod 0");
    if (!automatic || !full) GTEST_SKIP() << "no display and no xvfb-run";
    ASSERT_EQ(automatic->picture.rgb.size(), full->picture.rgb.size());
    ASSERT_EQ(automatic->picture.width, 256);
    // Measured: 21.3k triangles against 41.9k (the simplified coarse
    // bricks keep more of theirs where the normals turn fast: 15k before
    // the limit on turning normals).
    EXPECT_LT(5 * automatic->triangles, 3 * full->triangles) << "the far bricks were drawn coarser";
    const PictureDifference d = difference(automatic->picture, full->picture);
    // Measured: a mean of 0.16 (distance normals) and 0.23 levels
    // (density), 0.11-0.13% of the pixels above 24 (edges of the silhouette
    // moved by a fraction of a pixel).
    std::printf(
        "automatic vs full detail (%lld triangles against %lld), %s normals: mean %.2f, %.2f%% "
        "above 24\n",
        static_cast<long long>(automatic->triangles), static_cast<long long>(full->triangles),
        normals, d.mean, 100.0 * d.visible_share);
    EXPECT_LT(d.mean, 1.0) << normals;
    EXPECT_LT(d.visible_share, 0.005) << normals;
  }
}

// The drawn surface is simplified (a fifth of the triangles or fewer: only
// the vertices on the bricks' borders are held); at full detail, where a
// voxel spans more than a pixel, the picture must not show it: no facet,
// and no streak or wedge where a long triangle joins a crease to the smooth
// clay around it (the stars the demo's face showed around its eyes and
// mouth when the normals could turn without limit across a triangle: 0.063%
// of the pixels above 24, 0.395% above 8; the wedges beside the eye sockets
// when they could turn as far across a long one as across a short one:
// 0.020% and 0.075%).
TEST(StationWindow, TheSimplifiedSurfaceLooksLikeTheMarchedOne) {
  sculpt::test::ScratchDir dir;
  const std::string project = demo_project(dir);
  const auto simplified = shoot(dir, project, "--size 640x400 --lod 0");
  const auto marched = shoot(dir, project, "--size 640x400 --lod 0 --simplify-error 0");
  if (!simplified || !marched) GTEST_SKIP() << "no display and no xvfb-run";
  ASSERT_EQ(simplified->picture.rgb.size(), marched->picture.rgb.size());
  EXPECT_LT(5 * simplified->triangles, marched->triangles);
  const PictureDifference d = difference(simplified->picture, marched->picture);
  // Measured: 41.9k triangles against 234k, a mean of 0.07, 0.014% above
  // 24, 0.035% above 8.
  std::printf(
      "simplified (%lld triangles) vs marched (%lld): mean %.2f, %.3f%% above 24, %.3f%% above "
      "8\n",
      static_cast<long long>(simplified->triangles), static_cast<long long>(marched->triangles),
      d.mean, 100.0 * d.visible_share, 100.0 * d.faint_share);
  EXPECT_LT(d.mean, 1.0);
  EXPECT_LT(d.visible_share, 0.0002);
  EXPECT_LT(d.faint_share, 0.0004);
}

TEST(StationWindow, BadInputGetsOneClearError) {
  sculpt::test::ScratchDir dir;
  auto r = run_with_display("run --open " + dir.file("missing.sculpt") + " --frames 1 --hidden",
                            dir.path());
  if (!r) GTEST_SKIP() << "no display and no xvfb-run";
  EXPECT_EQ(r->exit_code, 1);
  EXPECT_NE(r->err.find("missing.sculpt"), std::string::npos) << r->err;
  EXPECT_EQ(line_count(r->err), 1) << r->err;
  r = run_with_display("run --device nosuch:device --frames 1 --hidden", dir.path());
  EXPECT_EQ(r->exit_code, 1);
  EXPECT_EQ(line_count(r->err), 1) << r->err;
  // Force devices: an unknown one, a missing hand script, a bad one.
  std::ofstream(dir.file("bad.hand")) << "sculpt-hand 1\nat 0 0 0\n";
  for (const std::string& id : {std::string("bogus"), "sim-arm:" + dir.file("missing.hand"),
                                "sim-arm:" + dir.file("bad.hand")}) {
    r = run_with_display("run --haptic " + id + " --frames 1 --hidden", dir.path());
    EXPECT_EQ(r->exit_code, 1) << id;
    EXPECT_NE(r->err.find("--haptic"), std::string::npos) << r->err;
    EXPECT_EQ(line_count(r->err), 1) << r->err;
  }
}

// The simulated arm as the station's only device (the bundled touch script):
// it rests the tool on the clay, carves with force, and its recording
// replays to the same sculpture. Counts and outcomes, not timings: the arm
// runs in real time on its own thread, whatever the frames do.
TEST(StationWindow, TheSimulatedArmCarvesWithForceAndItsRecordingReplays) {
  sculpt::test::ScratchDir dir;
  const std::string hand = std::string(SCULPT_SESSIONS_DIR) + "/touch.hand";
  auto r = run_with_display("run --haptic sim-arm:" + hand +
                                " --until-replayed --hidden --no-vsync --stats " +
                                dir.file("s.json") + " --record " + dir.file("touch.scs"),
                            dir.path());
  if (!r) GTEST_SKIP() << "no display and no xvfb-run";
  ASSERT_EQ(r->exit_code, 0) << r->err;
  const auto stats = nlohmann::json::parse(read_text(dir.file("s.json")));
  const auto& h = stats["haptics"];
  EXPECT_EQ(h["device"], "Simulated arm");
  EXPECT_EQ(h["ticks"].get<int64_t>(), 6200);  // the script unplugs the arm at 6.2 s
  EXPECT_GT(h["max_force_n"].get<double>(), 1.0);
  EXPECT_LE(h["max_force_n"].get<double>(), 8.0 + 1e-4);
  EXPECT_GE(h["patch"]["refreshes"].get<int64_t>(), 1);
  EXPECT_GT(stats["dabs"].get<int64_t>(), 10);
  EXPECT_GE(stats["strokes"].get<int64_t>(), 1);
  // Carved: less clay than the slab the window starts with (128^3 voxels).
  EXPECT_LT(stats["solid_voxels"].get<int64_t>(), 128 * 128 * 128);
  EXPECT_GT(stats["solid_voxels"].get<int64_t>(), 128 * 128 * 120);
  auto recorded = load_session(dir.file("touch.scs"));
  ASSERT_TRUE(recorded.ok()) << recorded.error().message();
  StationLoop loop(StationLoop::Options{});
  // The forces too: every tick the window's loop ran, run again bit for bit.
  HapticReplay haptics(loop, "touch");
  ReplayOptions ro;
  ro.on_haptic = [&](const sim::HapticRecord& record) { return haptics.handle(record); };
  ro.fast = true;
  ASSERT_TRUE(replay_session(*recorded, "touch", loop, ro).ok());
  EXPECT_EQ(loop.counters().dabs, stats["dabs"].get<int64_t>());
  EXPECT_EQ(loop.volume().content_hash(), stats["volume_hash"].get<uint64_t>());
  EXPECT_GT(haptics.figures().ticks, 6000);  // all but those before the recording began
  EXPECT_EQ(haptics.figures().force_mismatches, 0);
  EXPECT_EQ(haptics.figures().unverified_ticks, 0);
}

// A recorded force session played live: its commands move the tool, its
// recorded device readings drive the station's own loop (feel-only), and
// the sculpture is the recorded one.
TEST(StationWindow, ARecordedForceSessionPlaysLiveWithItsDevice) {
  sculpt::test::ScratchDir dir;
  const std::string touch = sim::bundled_session_path("touch");
  auto r =
      run_with_display("run --device sim:" + touch +
                           " --until-replayed --hidden --no-vsync --stats " + dir.file("s.json"),
                       dir.path());
  if (!r) GTEST_SKIP() << "no display and no xvfb-run";
  ASSERT_EQ(r->exit_code, 0) << r->err;
  const auto stats = nlohmann::json::parse(read_text(dir.file("s.json")));
  const auto& h = stats["haptics"];
  EXPECT_EQ(h["device"], "recorded force device (" + touch + ")");
  EXPECT_GT(h["ticks"].get<int64_t>(), 3000);  // it played, at about 1 kHz
  EXPECT_LE(h["max_force_n"].get<double>(), 8.0 + 1e-4);
  auto recorded = load_session(touch);
  ASSERT_TRUE(recorded.ok()) << recorded.error().message();
  StationLoop loop(StationLoop::Options{});
  ASSERT_TRUE(replay_fast(*recorded, "touch", loop).ok());
  EXPECT_EQ(loop.volume().content_hash(), stats["volume_hash"].get<uint64_t>());
}

}  // namespace
}  // namespace sculpt::station::test
