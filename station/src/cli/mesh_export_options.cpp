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

core::Mesh simplify_for_export(core::Mesh mesh, const core::MeshSimplifyOptions& options) {
  if (options.ratio >= 1.0 && options.max_error <= 0.0f) return mesh;
  const size_t before = mesh.triangles.size();
  core::SimplifiedMesh s = core::simplify_mesh(mesh, options);
  std::printf(
      "simplified  %zu -> %zu triangles, surface moved at most %.3f voxels (measured at "
      "every vertex of both)%s\n",
      before, s.mesh.triangles.size(), s.hausdorff,
      s.refused_attempts > 0 ? " (simplified again, less, to keep within the bound)" : "");
  return std::move(s.mesh);
}

}  // namespace sculpt::station::cli
