// sculpt mesh IN.nrrd [--iso V] [--lod K] [--ascii] [--check [--voxel-mm S]] -o OUT.{ply,obj,stl}
//
// Extracts the iso-surface of a uint8 volume at level of detail K with the
// per-brick marching cubes of the station (the same code the renderer's mesh
// cache runs), welds it across bricks and writes it in the format the
// output's extension names. Coordinates are level-0 voxel units.
// --check is the print check (core/mesh/print_check.h): a mesh that would not
// print (a hole, a surface through itself, inside out) is reported and
// nothing is written. `sculpt mesh IN.{stl,ply,obj} --check [-o OUT]` checks
// a mesh from anywhere (its units taken as --voxel-mm millimetres each) and
// writes it in OUT's format only when it would print.

#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "cli/commands.h"
#include "cli/field_options.h"
#include "cli/mesh_export_options.h"
#include "cli/number_checks.h"
#include "cli/progress_bar.h"
#include "sculpt/core/files/volume_file.h"
#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/mesh/mesh_io.h"
#include "sculpt/core/mesh/mesh_reader.h"
#include "sculpt/core/mesh/print_check.h"
#include "sculpt/core/util/parallel_for.h"
#include "sculpt/core/volume/volume_io.h"

namespace sculpt::station::cli {
namespace {

struct MeshOptions {
  std::string input;
  std::string output;
  float iso = 127.5f;
  int lod = 0;
  bool ascii = false;
  bool check = false;
  double voxel_mm = 1.0;
  core::MeshSimplifyOptions simplify;
  int threads = 0;
  DensityOptions density;
};

// What stops the mesh printing, in a few words.
std::string print_problems(const core::PrintCheck& c) {
  const core::MeshTopology& t = c.topology;
  std::string why;
  auto add = [&](int64_t n, const char* what) {
    if (n == 0) return;
    why += (why.empty() ? "" : ", ") + std::to_string(n) + " " + what;
  };
  add(t.boundary_edges, "boundary edges (holes: material cut by the block's faces?)");
  add(t.nonmanifold_edges, "edges in three or more triangles");
  add(t.misoriented_edges, "edges walked the same way twice (flipped triangles)");
  add(t.nonmanifold_vertices, "pinched vertices");
  add(t.degenerate_triangles, "degenerate triangles");
  add(c.self_intersections, "pairs of triangles through each other");
  if (t.faces == 0) why += why.empty() ? "no surface" : ", no surface";
  if (why.empty() && c.volume_mm3 <= 0) why = "the surface faces inward";
  return "the mesh would not print: " + why;
}

void print_check_report(const core::PrintCheck& c, double voxel_mm) {
  const core::MeshTopology& t = c.topology;
  const glm::vec3 size = c.bounds_mm.hi - c.bounds_mm.lo;
  std::printf("print check %s\n", c.printable() ? "printable" : "NOT printable");
  std::printf("  watertight  %s (%lld boundary edges, %lld misoriented)\n",
              t.closed() ? "yes" : "no", static_cast<long long>(t.boundary_edges),
              static_cast<long long>(t.misoriented_edges));
  std::printf("  manifold    %s (%lld non-manifold edges, %lld pinched vertices)\n",
              t.manifold() ? "yes" : "no", static_cast<long long>(t.nonmanifold_edges),
              static_cast<long long>(t.nonmanifold_vertices));
  std::printf("  intersects  %lld pairs of triangles\n",
              static_cast<long long>(c.self_intersections));
  std::printf("  parts       %lld\n", static_cast<long long>(c.components));
  std::printf("  volume      %.1f mm^3 (voxel %g mm)\n", c.volume_mm3, voxel_mm);
  std::printf("  size        %.2f x %.2f x %.2f mm\n", static_cast<double>(size.x),
              static_cast<double>(size.y), static_cast<double>(size.z));
}

// A mesh file in: simplified when asked, checked when asked (and then
// written only when it passes), written in the output's format.
int mesh_file(const MeshOptions& o) {
  const bool simplify = o.simplify.ratio < 1.0 || o.simplify.max_error > 0.0f;
  if (!o.check && !simplify)
    return report(Error(o.input + ": a mesh read in is checked (--check) or simplified "
                                  "(--simplify, --max-error); a volume is meshed"));
  if (!o.check && o.output.empty())
    return report(Error(o.input + ": --output is needed for the simplified mesh"));
  std::optional<core::MeshFormat> format;
  if (!o.output.empty()) {
    auto f = core::mesh_format_for(o.output, o.ascii);
    if (!f) return report(f.error());
    format = *f;
  }
  const auto read = core::read_mesh(o.input);
  if (!read) return report(read.error());
  std::printf("mesh        %s: %zu vertices, %zu triangles\n", o.input.c_str(),
              read->positions.size(), read->triangles.size());
  const core::Mesh mesh = simplify_for_export(*read, o.simplify);
  if (o.check) {
    const core::PrintCheck c = core::check_print(mesh, o.voxel_mm);
    print_check_report(c, o.voxel_mm);
    if (!c.printable()) return report(Error(o.input + ": " + print_problems(c)));
  }
  if (!format) return 0;
  if (Status st = core::write_mesh(o.output, mesh, *format); !st) return report(st.error());
  std::printf("wrote       %s\n", o.output.c_str());
  return 0;
}

int run_mesh(const MeshOptions& o) {
  if (core::mesh_format_for(o.input).ok()) return mesh_file(o);
  if (o.output.empty()) return report(Error(o.input + ": --output is needed for a volume's mesh"));
  // Check the output's name before the (possibly long) read.
  auto format = core::mesh_format_for(o.output, o.ascii);
  if (!format) return report(format.error());
  if (o.ascii && *format != core::MeshFormat::kPlyAscii) {
    return report(Error(o.output + ": --ascii applies to .ply output only"));
  }
  core::VolumeOptions vo;
  vo.threads = o.threads;
  using clock = std::chrono::steady_clock;
  ProgressBar bar("mesh");
  const auto t0 = clock::now();
  const auto window = density_window(o.density, o.input);
  if (!window) return report(window.error());
  auto volume = core::read_volume_file(o.input, vo, {}, window->has_value() ? &**window : nullptr);
  if (!volume) return report(volume.error());
  const auto t1 = clock::now();
  core::MeshCache cache(o.lod, core::MarchingCubesOptions{o.iso, o.threads});
  const core::MeshUpdate u = cache.update(*volume, bar.progress());
  if (bar.cancelled()) return bar.cancel_exit();
  bar.finish();
  const core::Mesh mesh = simplify_for_export(cache.welded_mesh(), o.simplify);
  const auto t2 = clock::now();
  if (o.check) {
    const core::PrintCheck c = core::check_print(mesh, o.voxel_mm);
    print_check_report(c, o.voxel_mm);
    if (!c.printable()) return report(Error(o.output + ": not written: " + print_problems(c)));
  }
  if (Status st = core::write_mesh(o.output, mesh, *format); !st) return report(st.error());
  const auto t3 = clock::now();

  const core::MeshTopology t = core::check_topology(mesh);
  const glm::ivec3 d = volume->dims();
  const glm::ivec3 ld = volume->level_dims(o.lod);
  auto seconds = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
  std::printf("volume      %dx%dx%d, level %d (%dx%dx%d), iso %g\n", d.x, d.y, d.z, o.lod, ld.x,
              ld.y, ld.z, static_cast<double>(o.iso));
  std::printf("bricks      %lld of %lld marched\n", static_cast<long long>(u.bricks_meshed),
              static_cast<long long>(volume->brick_count()));
  std::printf("mesh        %zu vertices, %zu triangles, %s, Euler characteristic %lld\n",
              mesh.positions.size(), mesh.triangles.size(),
              t.manifold() ? "closed manifold" : "NOT closed",
              static_cast<long long>(t.euler_characteristic()));
  std::printf("size        area %.2f voxel^2, volume %.2f voxel^3\n", core::surface_area(mesh),
              core::enclosed_volume(mesh));
  std::printf("time        read %.3f s, mesh %.3f s (%d threads), write %.3f s\n", seconds(t0, t1),
              seconds(t1, t2), o.threads > 0 ? o.threads : core::hardware_threads(),
              seconds(t2, t3));
  std::printf("wrote       %s\n", o.output.c_str());
  return 0;
}

}  // namespace

void add_mesh_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<MeshOptions>();
  CLI::App* cmd =
      app.add_subcommand("mesh", "Iso-surface of a volume (marching cubes) to PLY, OBJ or STL");
  cmd->add_option(
         "input", o->input,
         "NRRD (uint8 density, or any type with --window) or .vdb volume; or a mesh (.stl, .ply, "
         ".obj) to --check")
      ->required()
      ->check(input_file());
  add_density_options(cmd, o->density);
  cmd->add_option("-o,--output", o->output,
                  "output mesh: .ply, .obj, .stl or .glb (glTF 2.0; a checked mesh: written only "
                  "if it passes)");
  cmd->add_option("--iso", o->iso, "iso-level in density units, 0 <= V < 255 (default 127.5)")
      ->check(finite_range(0.0f, 254.999f));
  cmd->add_option("--lod", o->lod, "level of detail: 0 = full resolution .. 5 = 1/32")
      ->check(finite_range(0, 5));
  cmd->add_flag("--ascii", o->ascii, "ASCII instead of binary PLY");
  cmd->add_flag("--check", o->check,
                "print check: watertight, manifold, not through itself; volume and size in mm. "
                "A mesh that would not print is not written (exit 1)");
  cmd->add_option("--voxel-mm", o->voxel_mm,
                  "--check: millimetres per voxel (per unit of a mesh read in)")
      ->capture_default_str()
      ->check(finite_range(1e-6, 1e6));
  add_simplify_options(cmd, o->simplify);
  add_threads_option(cmd, o->threads);
  cmd->callback([o, &action] { action = [o] { return run_mesh(*o); }; });
}

}  // namespace sculpt::station::cli
