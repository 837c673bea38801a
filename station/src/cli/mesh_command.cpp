// sculpt mesh IN.{nrrd,vdb} [--iso V] [--lod K] [--ascii] [--check [--voxel-mm S]]
//            [--simplify R] [--max-error E] -o OUT.{ply,obj,stl,glb}
//
// Extracts the iso-surface of a uint8 volume at level of detail K with the
// per-brick marching cubes of the station (the same code the renderer's mesh
// cache runs), welds it across bricks and writes it in the format the
// output's extension names. Coordinates are level-0 voxel units.
// --check is the print check (core/mesh/print_check.h): a mesh that would not
// print (a hole, a surface through itself, inside out) is reported and
// nothing is written. `sculpt mesh IN.{stl,ply,obj} --check [-o OUT]` checks
// a mesh from anywhere (its units taken as --voxel-mm millimetres each) and
// writes it in OUT's format only when it would print. `sculpt export` to a
// mesh runs mesh_to_output() too.

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
#include "sculpt/core/files/mesh_file.h"
#include "sculpt/core/files/volume_file.h"
#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/mesh/mesh_io.h"
#include "sculpt/core/mesh/print_check.h"
#include "sculpt/core/util/parallel_for.h"
#include "sculpt/core/volume/volume_io.h"

namespace sculpt::station::cli {
namespace {

// A mesh file in: simplified when asked, checked when asked (and then
// written only when it passes), written in the output's format.
int mesh_file(const MeshCliOptions& o) {
  const core::MeshSimplifyOptions& simplify = o.mesh.simplify;
  const bool simplifies = simplify.ratio < 1.0 || simplify.max_error > 0.0f;
  if (!o.mesh.check && !simplifies)
    return report(Error(o.input + ": a mesh read in is checked (--check) or simplified "
                                  "(--simplify, --max-error); a volume is meshed"));
  if (!o.mesh.check && o.output.empty())
    return report(Error(o.input + ": --output is needed for the simplified mesh"));
  std::optional<core::MeshFormat> format;
  if (!o.output.empty()) {
    auto f = mesh_export_format(o.output, o.mesh);
    if (!f) return report(f.error());
    format = *f;
  }
  auto read = core::read_mesh_file(o.input);
  if (!read) return report(read.error());
  std::printf("mesh        %s: %zu vertices, %zu triangles\n", o.input.c_str(),
              read->positions.size(), read->triangles.size());
  const auto mesh = prepare_mesh_export(std::move(*read), o.mesh, o.input);
  if (!mesh) return report(mesh.error());
  if (!format) return 0;
  if (Status st = core::write_mesh(o.output, *mesh, *format); !st) return report(st.error());
  std::printf("wrote       %s\n", o.output.c_str());
  return 0;
}

}  // namespace

int mesh_to_output(const MeshCliOptions& o) {
  if (core::is_mesh_file_name(o.input)) return mesh_file(o);
  if (o.output.empty()) return report(Error(o.input + ": --output is needed for a volume's mesh"));
  // Check the output's name before the (possibly long) read.
  auto format = mesh_export_format(o.output, o.mesh);
  if (!format) return report(format.error());
  core::VolumeOptions vo;
  vo.threads = o.threads;
  using clock = std::chrono::steady_clock;
  ProgressBar bar("mesh");
  const auto t0 = clock::now();
  auto volume = read_volume_input(o.input, o.density, vo);
  if (!volume) return report(volume.error());
  const auto t1 = clock::now();
  core::MeshCache cache(o.lod, core::MarchingCubesOptions{o.iso, o.threads});
  const core::MeshUpdate u = cache.update(*volume, bar.progress());
  if (bar.cancelled()) return bar.cancel_exit();
  bar.finish();
  const auto prepared =
      prepare_mesh_export(cache.welded_mesh(), o.mesh, o.output + ": not written");
  if (!prepared) return report(prepared.error());
  const core::Mesh& mesh = *prepared;
  const auto t2 = clock::now();
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

void add_mesh_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<MeshCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "mesh", "Iso-surface of a volume (marching cubes) to PLY, OBJ, STL or glTF");
  cmd->add_option(
         "input", o->input,
         "NRRD (uint8 density, or any type with --window) or .vdb volume; or a mesh (.glb, .stl, "
         ".ply, .obj) to --check or simplify")
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
  add_mesh_export_options(cmd, o->mesh);
  add_threads_option(cmd, o->threads);
  cmd->callback([o, &action] { action = [o] { return mesh_to_output(*o); }; });
}

}  // namespace sculpt::station::cli
