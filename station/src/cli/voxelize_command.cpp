// sculpt voxelize MESH (--size N | --voxel-mm S [--unit-mm U]) [--sdf] [--margin M]
//                      [--threads T] -o OUT.{nrrd,vdb}
//
// A closed triangle mesh (OBJ, PLY, STL or glTF .glb) to a volume (Jones &
// Satherley §3.2): the exact signed distance to the triangles (sign by
// angle-weighted pseudonormals), written as float32 (--sdf) or as uint8
// density (the project's 2-voxel ramp, iso 127.5 on the surface).
// Mapping with --size: the mesh's bounding box is centred at ((N-1)/2,
// (N-1)/2, (N-1)/2), its longest side scaled to N - 1 - 2 M voxels (M =
// --margin, default 4). With --voxel-mm: the mesh keeps its size, each voxel
// S mm (a mesh unit U mm: glTF is metres, so 1000 for .glb, else 1), in the
// smallest box that holds it with M voxels of margin on each side.
// `sculpt import MESH` runs this same function.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/field_options.h"
#include "cli/number_checks.h"
#include "cli/progress_bar.h"
#include "sculpt/core/distance/distance_io.h"
#include "sculpt/core/distance/mesh_distance.h"
#include "sculpt/core/files/mesh_file.h"
#include "sculpt/core/io/nrrd.h"

namespace sculpt::station::cli {
namespace {

constexpr int kMinEdge = 8, kMaxEdge = 1024;

struct Placement {
  glm::ivec3 dims;
  core::VoxelizeMapping map;
};

// The grid and the mapping the options ask for.
Result<Placement> place_mesh(const core::Mesh& mesh, const VoxelizeCliOptions& o) {
  if (o.size > 0) {
    if (2.0f * o.margin >= float(o.size - 2))
      return Error("--margin " + std::to_string(o.margin) + " leaves no room in --size " +
                   std::to_string(o.size));
    auto fitted = core::fit_mesh_to_grid(mesh, o.size, o.margin);
    if (!fitted) return fitted.error().in(o.input);
    return Placement{glm::ivec3(o.size), *fitted};
  }
  const double unit_mm = o.unit_mm > 0 ? o.unit_mm : core::mesh_unit_mm(o.input);
  const double scale = unit_mm / o.voxel_mm;  // voxels per mesh unit
  const core::MeshBounds b = core::mesh_bounds(mesh);
  const glm::dvec3 lo(b.lo), hi(b.hi);
  const glm::dvec3 span = (hi - lo) * scale;
  Placement p;
  for (int a = 0; a < 3; ++a) {
    const double edge = std::ceil(span[a]) + 1.0 + 2.0 * o.margin;
    if (!std::isfinite(edge) || edge > kMaxEdge) {
      char text[200];
      std::snprintf(text, sizeof text,
                    "%s: at --voxel-mm %g (a mesh unit %g mm) the mesh spans %.0f voxels, more "
                    "than %d: give a larger --voxel-mm or --size",
                    o.input.c_str(), o.voxel_mm, unit_mm, span[a], kMaxEdge);
      return Error(text);
    }
    p.dims[a] = std::max(kMinEdge, static_cast<int>(edge));
  }
  p.map.scale = static_cast<float>(scale);
  const glm::dvec3 offset = (glm::dvec3(p.dims) - 1.0) * 0.5 - (lo + hi) * 0.5 * scale;
  p.map.offset = glm::vec3(offset);
  if (!(p.map.scale > 0.0f) || !std::isfinite(p.map.scale) || !std::isfinite(p.map.offset.x) ||
      !std::isfinite(p.map.offset.y) || !std::isfinite(p.map.offset.z))
    return Error(o.input + ": its position cannot be mapped to the grid in float precision");
  return p;
}

}  // namespace

int voxelize_to_output(const VoxelizeCliOptions& o) {
  if ((o.size > 0) == (o.voxel_mm > 0))
    return report(Error(o.input + ": give the grid as --size N or --voxel-mm S (one of them)"));
  using clock = std::chrono::steady_clock;
  ProgressBar bar("voxelize");
  const auto t0 = clock::now();
  auto mesh = core::read_mesh_file(o.input);
  if (!mesh) return report(mesh.error());
  const core::MeshTopology topo = core::check_topology(*mesh);
  if (!topo.closed())
    return report(Error(o.input + ": mesh is not closed (" + std::to_string(topo.boundary_edges) +
                        " boundary, " + std::to_string(topo.nonmanifold_edges) + " non-manifold, " +
                        std::to_string(topo.misoriented_edges) +
                        " mis-oriented edges): inside and outside are undefined"));
  const Result<Placement> placed_at = place_mesh(*mesh, o);
  if (!placed_at) return report(placed_at.error());
  const core::VoxelizeMapping& map = placed_at->map;
  const glm::ivec3 dims = placed_at->dims;
  const core::Mesh placed = core::transform_mesh(*mesh, map);
  const auto t1 = clock::now();
  const core::MeshDistance md(placed);
  const core::DenseGrid<float> field =
      core::mesh_signed_distance(md, dims, o.threads, bar.progress());
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
  std::printf("wrote       %s (%dx%dx%d, %s)\n", o.output.c_str(), dims.x, dims.y, dims.z,
              field_kind(o.sdf));
  return 0;
}

void add_voxelize_grid_options(CLI::App* cmd, VoxelizeCliOptions& o) {
  auto* size = cmd->add_option("--size", o.size, "grid edge N (N^3 voxels, 8..1024)")
                   ->check(finite_range(kMinEdge, kMaxEdge));
  cmd->add_option("--voxel-mm", o.voxel_mm,
                  "instead of --size: each voxel S mm, the mesh keeping its size (the grid is the "
                  "smallest box that holds it)")
      ->check(finite_range(1e-6, 1e6))
      ->excludes(size);
  cmd->add_option("--unit-mm", o.unit_mm,
                  "with --voxel-mm: millimetres per mesh unit (default 1000 for .glb, glTF "
                  "being metres; 1 for .stl, .obj, .ply)")
      ->check(finite_range(1e-9, 1e9));
  cmd->add_option("--margin", o.margin, "voxels between the mesh and the grid's faces (default 4)")
      ->check(finite_range(0.0f, 256.0f));
  cmd->add_flag("--sdf", o.sdf, "write the float32 signed distance instead of uint8 density");
  add_threads_option(cmd, o.threads);
}

void add_voxelize_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<VoxelizeCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "voxelize", "Closed mesh (OBJ/PLY/STL/GLB) to a density or signed distance volume");
  cmd->add_option("input", o->input, "mesh: .obj, .ply, .stl or .glb (glTF 2.0 binary)")
      ->required()
      ->check(input_file());
  cmd->add_option("-o,--output", o->output, "output volume (.nrrd or .vdb)")->required();
  add_voxelize_grid_options(cmd, *o);
  cmd->callback([o, &action] { action = [o] { return voxelize_to_output(*o); }; });
}

}  // namespace sculpt::station::cli
