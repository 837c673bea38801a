// sculpt offset IN.nrrd --by D [--sdf] [--threads N] -o OUT.nrrd
//
// Moves the surface along its normals by D voxels (D > 0 inflates, D < 0
// deflates) on the sub-voxel signed distance field: the new surface is
// {distance = D}. Output: uint8 density for a uint8 input, float32 signed
// distance for a float32 input or with --sdf.

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

struct OffsetOptions {
  std::string input, output;
  float by = 0;
  bool sdf = false;
  int threads = 0;
};

int run_offset(const OffsetOptions& o) {
  ProgressBar bar("offset");
  auto in = core::read_surface_file(o.input);
  if (!in) return report(in.error());
  // A float output is a distance field, which does not exist without a
  // surface; a density output of an empty or solid block is that block.
  if (o.sdf || !in->from_density)
    if (Status st = core::require_surface(*in, o.input); !st) return report(st.error());
  const core::DenseGrid<float> moved =
      core::offset_distance(core::surface_distance(in->phi, o.threads, bar.progress()), o.by);
  if (bar.cancelled()) return bar.cancel_exit();
  bar.finish();
  const bool as_float = o.sdf || !in->from_density;
  const Status st = write_field(o.output, moved, as_float);
  if (!st) return report(st.error());
  int64_t before = 0, after = 0;
  for (size_t i = 0; i < moved.size(); ++i) {
    before += in->phi[i] < 0.0f;
    after += moved[i] < 0.0f;
  }
  std::printf("offset      by %+.3g voxels: %lld -> %lld inside voxels\n", double(o.by),
              static_cast<long long>(before), static_cast<long long>(after));
  std::printf("wrote       %s (%s)\n", o.output.c_str(), field_kind(as_float));
  return 0;
}

}  // namespace

void add_offset_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<OffsetOptions>();
  CLI::App* cmd =
      app.add_subcommand("offset", "Inflate (D > 0) or deflate (D < 0) a surface by D voxels");
  cmd->add_option("input", o->input, "uint8 density or float32 NRRD, or .vdb")
      ->required()
      ->check(input_file());
  cmd->add_option("-o,--output", o->output, "output volume (.nrrd or .vdb)")->required();
  cmd->add_option("--by", o->by, "offset D, voxels")
      ->required()
      ->check(finite_range(-1024.0f, 1024.0f));
  cmd->add_flag("--sdf", o->sdf, "write the float32 signed distance");
  add_threads_option(cmd, o->threads);
  cmd->callback([o, &action] { action = [o] { return run_offset(*o); }; });
}

}  // namespace sculpt::station::cli
