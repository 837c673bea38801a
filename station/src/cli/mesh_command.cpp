// sculpt mesh IN.nrrd [--iso V] [--lod K] [--ascii] -o OUT.{ply,obj,stl}
//
// Extracts the iso-surface of a uint8 volume at level of detail K with the
// per-brick marching cubes of the station (the same code the renderer's mesh
// cache runs), welds it across bricks and writes it in the format the
// output's extension names. Coordinates are level-0 voxel units.

#include <chrono>
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/field_options.h"
#include "cli/number_checks.h"
#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/mesh/mesh_io.h"
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
  int threads = 0;
  DensityOptions density;
};

int run_mesh(const MeshOptions& o) {
  // Check the output's name before the (possibly long) read.
  auto format = core::mesh_format_for(o.output, o.ascii);
  if (!format) return report(format.error());
  if (o.ascii && *format != core::MeshFormat::kPlyAscii) {
    return report(Error(o.output + ": --ascii applies to .ply output only"));
  }
  core::VolumeOptions vo;
  vo.threads = o.threads;
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  const auto window = density_window(o.density, o.input);
  if (!window) return report(window.error());
  auto volume = core::read_volume_nrrd(o.input, vo, {}, window->has_value() ? &**window : nullptr);
  if (!volume) return report(volume.error());
  const auto t1 = clock::now();
  core::MeshCache cache(o.lod, core::MarchingCubesOptions{o.iso, o.threads});
  const core::MeshUpdate u = cache.update(*volume);
  const core::Mesh mesh = cache.welded_mesh();
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

}  // namespace

void add_mesh_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<MeshOptions>();
  CLI::App* cmd =
      app.add_subcommand("mesh", "Iso-surface of a volume (marching cubes) to PLY, OBJ or STL");
  cmd->add_option("input", o->input, "NRRD volume (uint8 density, or any type with --window)")
      ->required()
      ->check(input_file());
  add_density_options(cmd, o->density);
  cmd->add_option("-o,--output", o->output, "output mesh: .ply, .obj or .stl")->required();
  cmd->add_option("--iso", o->iso, "iso-level in density units, 0 <= V < 255 (default 127.5)")
      ->check(finite_range(0.0f, 254.999f));
  cmd->add_option("--lod", o->lod, "level of detail: 0 = full resolution .. 5 = 1/32")
      ->check(finite_range(0, 5));
  cmd->add_flag("--ascii", o->ascii, "ASCII instead of binary PLY");
  add_threads_option(cmd, o->threads);
  cmd->callback([o, &action] { action = [o] { return run_mesh(*o); }; });
}

}  // namespace sculpt::station::cli
