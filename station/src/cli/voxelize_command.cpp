// sculpt voxelize MESH --size N [--sdf] [--margin M] [--threads T] -o OUT.nrrd
//
// A closed triangle mesh (OBJ, PLY or STL) to an N^3 volume (Jones &
// Satherley §3.2): the exact signed distance to the triangles (sign by
// angle-weighted pseudonormals), written as float32 (--sdf) or as uint8
// density (the project's 2-voxel ramp, iso 127.5 on the surface). Mapping:
// the mesh's bounding box is centred at ((N-1)/2, (N-1)/2, (N-1)/2), its
// longest side scaled to N - 1 - 2 M voxels (M = --margin, default 4).

#include <chrono>
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/field_options.h"
#include "cli/number_checks.h"
#include "cli/progress_bar.h"
#include "sculpt/core/distance/distance_io.h"
#include "sculpt/core/distance/mesh_distance.h"
#include "sculpt/core/io/nrrd.h"
#include "sculpt/core/mesh/mesh_reader.h"

namespace sculpt::station::cli {
namespace {

struct VoxelizeOptions {
  std::string input, output;
  int size = 128;
  float margin = 4.0f;
  bool sdf = false;
  int threads = 0;
};

int run_voxelize(const VoxelizeOptions& o) {
  if (2.0f * o.margin >= float(o.size - 2))
    return report(Error("--margin " + std::to_string(o.margin) + " leaves no room in --size " +
                        std::to_string(o.size)));
  using clock = std::chrono::steady_clock;
  ProgressBar bar("voxelize");
  const auto t0 = clock::now();
  auto mesh = core::read_mesh(o.input);
  if (!mesh) return report(mesh.error());
  const core::MeshTopology topo = core::check_topology(*mesh);
  if (!topo.closed())
    return report(Error(o.input + ": mesh is not closed (" + std::to_string(topo.boundary_edges) +
                        " boundary, " + std::to_string(topo.nonmanifold_edges) + " non-manifold, " +
                        std::to_string(topo.misoriented_edges) +
                        " mis-oriented edges): inside and outside are undefined"));
  const Result<core::VoxelizeMapping> fitted = core::fit_mesh_to_grid(*mesh, o.size, o.margin);
  if (!fitted) return report(fitted.error().in(o.input));
  const core::VoxelizeMapping& map = *fitted;
  const core::Mesh placed = core::transform_mesh(*mesh, map);
  const auto t1 = clock::now();
  const core::MeshDistance md(placed);
  const core::DenseGrid<float> field =
      core::mesh_signed_distance(md, glm::ivec3(o.size), o.threads, bar.progress());
  const auto t2 = clock::now();
  if (bar.cancelled()) return bar.cancel_exit();
  bar.finish();
  // A mesh wound clockwise (inward normals) reads as inside-out: every
  // voxel on the border would be inside.
  if (field.at(0, 0, 0) < 0.0f)
    return report(Error(o.input + ": triangles face inward (wound clockwise seen from outside)"));
  const Status st = write_field(o.output, field, o.sdf);
  if (!st) return report(st.error());
  auto sec = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
  std::printf("mesh        %zu vertices, %zu triangles, closed\n", mesh->positions.size(),
              mesh->triangles.size());
  std::printf("mapping     grid = mesh * %.6g + (%.6g, %.6g, %.6g)\n", double(map.scale),
              double(map.offset.x), double(map.offset.y), double(map.offset.z));
  std::printf("time        read %.3f s, distance %.3f s\n", sec(t0, t1), sec(t1, t2));
  std::printf("wrote       %s (%d^3, %s)\n", o.output.c_str(), o.size, field_kind(o.sdf));
  return 0;
}

}  // namespace

void add_voxelize_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<VoxelizeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "voxelize", "Closed mesh (OBJ/PLY/STL) to a density or signed distance volume");
  cmd->add_option("input", o->input, "mesh: .obj, .ply or .stl")->required()->check(input_file());
  cmd->add_option("-o,--output", o->output, "output volume (.nrrd or .vdb)")->required();
  cmd->add_option("--size", o->size, "grid edge N (N^3 voxels, 8..1024)")
      ->required()
      ->check(finite_range(8, 1024));
  cmd->add_option("--margin", o->margin, "voxels between the mesh and the grid's faces (default 4)")
      ->check(finite_range(0.0f, 256.0f));
  cmd->add_flag("--sdf", o->sdf, "write the float32 signed distance instead of uint8 density");
  add_threads_option(cmd, o->threads);
  cmd->callback([o, &action] { action = [o] { return run_voxelize(*o); }; });
}

}  // namespace sculpt::station::cli
