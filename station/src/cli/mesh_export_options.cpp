#include "cli/mesh_export_options.h"

#include <cstdio>
#include <utility>

#include "cli/number_checks.h"

namespace sculpt::station::cli {

void add_simplify_options(CLI::App* command, core::MeshSimplifyOptions& options) {
  command
      ->add_option("--simplify", options.ratio,
                   "keep at most this share of the triangles, (0, 1] (the surface stays closed)")
      ->check(finite_range(1e-6, 1.0));
  command
      ->add_option("--max-error", options.max_error,
                   "simplify while the surface moves at most this many voxels (measured)")
      ->check(finite_range(1e-6, 1e6));
}

void add_mesh_export_options(CLI::App* command, MeshExportOptions& options) {
  add_simplify_options(command, options.simplify);
  command->add_flag("--check", options.check,
                    "print check: watertight, manifold, not through itself; volume and size in "
                    "mm. A mesh that would not print is not written (exit 1); it is not repaired");
  command
      ->add_option("--voxel-mm", options.voxel_mm,
                   "--check: millimetres per voxel (per unit of a mesh read in)")
      ->capture_default_str()
      ->check(finite_range(1e-6, 1e6));
  command->add_flag("--ascii", options.ascii, "ASCII instead of binary PLY");
}

Result<core::MeshFormat> mesh_export_format(const std::string& output,
                                            const MeshExportOptions& options) {
  auto format = core::mesh_format_for(output, options.ascii);
  if (!format) return format.error();
  if (options.ascii && *format != core::MeshFormat::kPlyAscii)
    return Error(output + ": --ascii applies to .ply output only");
  return *format;
}

core::Mesh simplify_for_export(core::Mesh mesh, const core::MeshSimplifyOptions& options) {
  if (options.ratio >= 1.0 && options.max_error <= 0.0f) return mesh;
  const size_t before = mesh.triangles.size();
  core::SimplifiedMesh s = core::simplify_mesh(mesh, options);
  std::printf(
      "simplified  %zu -> %zu triangles, surface moved at most %.3f voxels (measured at "
      "every vertex of both)%s\n",
      before, s.mesh.triangles.size(), s.hausdorff,
      s.refused_attempts > 0 ? " (simplified again, less, to keep within the bound)" : "");
  if (s.held_places > 0)
    std::printf(
        "            kept as it was in %d places where simplifying made the surface pass "
        "through itself\n",
        s.held_places);
  return std::move(s.mesh);
}

Result<core::Mesh> prepare_mesh_export(core::Mesh mesh, const MeshExportOptions& options,
                                       const std::string& name) {
  core::Mesh out = simplify_for_export(std::move(mesh), options.simplify);
  if (options.check) {
    const core::PrintCheck c = core::check_print(out, options.voxel_mm);
    print_check_report(c, options.voxel_mm);
    if (!c.printable()) return Error(name + ": " + print_problems(c));
  }
  return out;
}

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
  if (t.faces == 0) {
    std::printf("  size        none (no surface)\n");
    return;
  }
  std::printf("  size        %.2f x %.2f x %.2f mm\n", static_cast<double>(size.x),
              static_cast<double>(size.y), static_cast<double>(size.z));
}

}  // namespace sculpt::station::cli
