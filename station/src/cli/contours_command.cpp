// sculpt contours IN.txt [--sdf] [--threads N] -o OUT.nrrd|.ply|.obj|.stl
//
// Contour connection (Jones & Satherley §4.1): a stack of closed 2D contours
// (the text format of core/distance/contours.h) into a closed surface through
// the distance field. .nrrd: uint8 density (float32 signed distance with
// --sdf); a mesh extension: the iso-surface, normals from the distance
// field's gradient.

#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/field_options.h"
#include "cli/number_checks.h"
#include "sculpt/core/distance/contours.h"
#include "sculpt/core/distance/distance_io.h"
#include "sculpt/core/distance/distance_normals.h"
#include "sculpt/core/io/nrrd.h"
#include "sculpt/core/mesh/marching_cubes.h"
#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/mesh/mesh_io.h"

namespace sculpt::station::cli {
namespace {

struct ContoursOptions {
  std::string input, output;
  bool sdf = false;
  int threads = 0;
};

int run_contours(const ContoursOptions& o) {
  const std::filesystem::path out(o.output);
  std::string ext = out.extension().string();
  for (char& c : ext)
    c = char(std::tolower(static_cast<unsigned char>(c)));
  const bool volume_out = ext == ".nrrd" || ext == ".vdb";
  core::MeshFormat format = core::MeshFormat::kPlyBinary;
  if (!volume_out) {
    auto f = core::mesh_format_for(out);
    if (!f) return report(Error(o.output + ": output must be .nrrd, .vdb, .ply, .obj or .stl"));
    format = *f;
    if (o.sdf)
      return report(Error(o.output + ": --sdf applies to volume output (.nrrd, .vdb) only"));
  }
  auto stack = core::read_contours(o.input);
  if (!stack) return report(stack.error());
  const core::DenseGrid<float> field = core::contour_distance_field(*stack, o.threads);
  Status st;
  if (volume_out) {
    st = write_field(out, field, o.sdf);
  } else {
    const core::DenseGrid<uint8_t> density = core::density_from_distance_field(field);
    core::VolumeOptions vo;
    vo.threads = o.threads;
    const core::Volume volume = core::Volume::from_dense(density, vo);
    core::Mesh mesh =
        core::marching_cubes(volume, 0, core::MarchingCubesOptions{127.5f, o.threads});
    core::set_normals_from_distance(field, mesh);
    const core::MeshTopology t = core::check_topology(mesh);
    std::printf(
        "mesh        %zu vertices, %zu triangles, %s, %lld components, Euler characteristic %lld\n",
        mesh.positions.size(), mesh.triangles.size(), t.closed() ? "closed" : "NOT closed",
        static_cast<long long>(core::component_count(mesh)),
        static_cast<long long>(t.euler_characteristic()));
    st = core::write_mesh(out, mesh, format);
  }
  if (!st) return report(st.error());
  const glm::ivec3 d = stack->dims;
  std::printf("contours    %zu in a %dx%dx%d grid\n", stack->contours.size(), d.x, d.y, d.z);
  std::printf("wrote       %s\n", o.output.c_str());
  return 0;
}

}  // namespace

void add_contours_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<ContoursOptions>();
  CLI::App* cmd =
      app.add_subcommand("contours", "Stack of 2D contours to a closed surface (volume or mesh)");
  cmd->add_option("input", o->input, "contour text file (sculpt-contours 1)")
      ->required()
      ->check(input_file());
  cmd->add_option("-o,--output", o->output, "output: .nrrd, .vdb, .ply, .obj or .stl")->required();
  cmd->add_flag("--sdf", o->sdf,
                "write the signed distance (.nrrd as float32, .vdb as a level set)");
  add_threads_option(cmd, o->threads);
  cmd->callback([o, &action] { action = [o] { return run_contours(*o); }; });
}

}  // namespace sculpt::station::cli
