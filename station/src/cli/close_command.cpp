// sculpt close IN.nrrd --radius R [--sdf] [--threads N] -o OUT.nrrd
//
// True 3D closing (Jones & Satherley §4.2) on the sub-voxel distance field:
// dilate to the level R, re-compute the distance to that surface, erode by
// R. Fills gaps and cavities narrower than 2R and rounds concave corners to
// radius R; convex parts stay where they were. Output: uint8 density for a
// uint8 input, float32 signed distance for a float32 input or with --sdf.

#include <chrono>
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/field_options.h"
#include "cli/number_checks.h"
#include "cli/progress_bar.h"
#include "sculpt/core/distance/distance_io.h"
#include "sculpt/core/distance/morphology.h"
#include "sculpt/core/files/volume_file.h"
#include "sculpt/core/io/nrrd.h"

namespace sculpt::station::cli {
namespace {

struct CloseOptions {
  std::string input, output;
  float radius = 0;
  bool sdf = false;
  int threads = 0;
};

int run_close(const CloseOptions& o) {
  ProgressBar bar("close");
  const auto t0 = std::chrono::steady_clock::now();
  auto in = core::read_surface_file(o.input);
  if (!in) return report(in.error());
  // A float output is a distance field, which does not exist without a
  // surface; a density output of an empty or solid block is that block.
  if (o.sdf || !in->from_density)
    if (Status st = core::require_surface(*in, o.input); !st) return report(st.error());
  const core::DenseGrid<float> closed =
      core::close_distance(in->phi, o.radius, o.threads, bar.progress());
  if (bar.cancelled()) return bar.cancel_exit();
  bar.finish();
  const bool as_float = o.sdf || !in->from_density;
  const Status st = write_field(o.output, closed, as_float);
  if (!st) return report(st.error());
  int64_t inside_before = 0, inside_after = 0;
  for (size_t i = 0; i < closed.size(); ++i) {
    inside_before += in->phi[i] < 0.0f;
    inside_after += closed[i] < 0.0f;
  }
  std::printf("closed      radius %.3g voxels: %lld -> %lld inside voxels\n", double(o.radius),
              static_cast<long long>(inside_before), static_cast<long long>(inside_after));
  std::printf("time        %.3f s\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  std::printf("wrote       %s (%s)\n", o.output.c_str(), field_kind(as_float));
  return 0;
}

}  // namespace

void add_close_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<CloseOptions>();
  CLI::App* cmd =
      app.add_subcommand("close", "True 3D morphological closing on the distance field");
  cmd->add_option("input", o->input, "uint8 density or float32 NRRD, or .vdb")
      ->required()
      ->check(input_file());
  cmd->add_option("-o,--output", o->output, "output volume (.nrrd or .vdb)")->required();
  cmd->add_option("--radius", o->radius, "closing radius, voxels (> 0)")
      ->required()
      ->check(finite_range(0.001f, 1024.0f));
  cmd->add_flag("--sdf", o->sdf, "write the float32 signed distance");
  add_threads_option(cmd, o->threads);
  cmd->callback([o, &action] { action = [o] { return run_close(*o); }; });
}

}  // namespace sculpt::station::cli
