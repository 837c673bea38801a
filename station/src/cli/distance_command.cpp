// sculpt distance IN.nrrd [--method M] [--init binary|shell] [--threads N] -o OUT.nrrd
// sculpt distance --table [--sizes 128,256] [--methods M,M] [--threads N]
//
// The signed distance field of a volume's surface (Jones & Satherley §3):
// float32 NRRD, voxel units, negative inside. IN is uint8 density (inside:
// density above 127.5) or float32 (inside: negative). --table runs the §3.7
// comparison on an off-grid sphere and a torus and prints it as Markdown.

#include <chrono>
#include <cstdio>
#include <memory>
#include <sstream>

#include "cli/commands.h"
#include "cli/field_options.h"
#include "cli/number_checks.h"
#include "cli/progress_bar.h"
#include "sculpt/core/distance/distance_comparison.h"
#include "sculpt/core/distance/distance_io.h"
#include "sculpt/core/distance/signed_distance.h"
#include "sculpt/core/files/volume_file.h"
#include "sculpt/core/io/nrrd.h"
#include "sculpt/core/util/parallel_for.h"

namespace sculpt::station::cli {
namespace {

// brute is O(n m): beyond this many voxels it would run for hours.
constexpr int64_t kBruteMaxVoxels = int64_t{96} * 96 * 96;

struct DistanceOptions {
  std::string input, output, method = "exact", init = "shell";
  bool table = false;
  std::string sizes = "128,256", methods;
  int threads = 0;
};

int run_table(const DistanceOptions& o) {
  std::vector<core::ComparisonCase> cases;
  if (o.methods.empty()) {
    cases = core::default_comparison_cases();
  } else {
    std::stringstream s(o.methods);
    std::string name;
    while (std::getline(s, name, ',')) {
      auto m = core::parse_distance_method(name);
      if (!m) return report(m.error());
      for (auto init : {core::DistanceInit::kBinary, core::DistanceInit::kShell})
        cases.push_back({*m, init});
    }
  }
  std::vector<int> sizes;
  std::stringstream s(o.sizes);
  for (std::string word; std::getline(s, word, ',');) {
    int n = 0;
    try {
      n = std::stoi(word);
    } catch (...) {
    }
    if (n < 8 || n > 512) return report(Error("--sizes: '" + word + "' is not a size in 8..512"));
    sizes.push_back(n);
  }
  for (const auto& c : cases)
    for (int n : sizes)
      if (c.method == core::DistanceMethod::kBrute && int64_t(n) * n * n > kBruteMaxVoxels)
        return report(Error("--methods: brute is O(n^2); use it on sizes up to 96"));
  std::vector<core::ComparisonRow> rows;
  for (int n : sizes)
    for (auto shape : {core::ComparisonShape::kSphere, core::ComparisonShape::kTorus}) {
      const core::ComparisonInput input = core::comparison_input(shape, n);
      auto r = core::compare_distance_methods(input, cases, o.threads);
      rows.insert(rows.end(), r.begin(), r.end());
    }
  std::printf("threads %d; time = transform + initialisation (B or the shell)\n\n%s",
              o.threads > 0 ? o.threads : core::default_threads(),
              core::comparison_markdown(rows).c_str());
  return 0;
}

int run_distance(const DistanceOptions& o) {
  if (o.table) return run_table(o);
  if (o.input.empty()) return report(Error("distance: needs an input volume (or --table)"));
  if (o.output.empty()) return report(Error("distance: needs an output file (-o OUT.nrrd)"));
  auto method = core::parse_distance_method(o.method);
  if (!method) return report(method.error());
  auto init = core::parse_distance_init(o.init);
  if (!init) return report(init.error());
  using clock = std::chrono::steady_clock;
  ProgressBar bar("distance");
  const auto t0 = clock::now();
  auto in = core::read_surface_file(o.input);
  if (!in) return report(in.error());
  const glm::ivec3 d = in->phi.dims();
  if (*method == core::DistanceMethod::kBrute && core::voxel_count(d) > kBruteMaxVoxels)
    return report(Error(o.input + ": " + std::to_string(d.x) + "x" + std::to_string(d.y) + "x" +
                        std::to_string(d.z) +
                        " is too large for --method brute (O(n^2), at most 96^3); use "
                        "exact or octree"));
  if (Status st = core::require_surface(*in, o.input); !st) return report(st.error());
  const auto t1 = clock::now();
  // The shell takes about a third of the exact transform's time.
  core::SubProgress preparing(bar.progress(), 0.0, 0.3), computing(bar.progress(), 0.3, 1.0);
  const core::DistanceInput prepared =
      core::prepare_distance_input(std::move(in->phi), *init, o.threads, preparing.get());
  if (bar.cancelled()) return bar.cancel_exit();
  const auto t2 = clock::now();
  const core::DenseGrid<float> field =
      core::compute_signed_distance(prepared, *method, *init, o.threads, computing.get());
  const auto t3 = clock::now();
  if (bar.cancelled()) return bar.cancel_exit();
  bar.finish();
  if (Status st = core::write_distance_file(o.output, field); !st) return report(st.error());
  float lo = 0, hi = 0;
  for (float v : field.values()) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  auto sec = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
  std::printf("volume      %dx%dx%d (%s)\n", d.x, d.y, d.z,
              in->from_density ? "uint8 density" : "float32 field");
  std::printf("method      %s, init %s\n", o.method.c_str(), o.init.c_str());
  if (prepared.shell)
    std::printf("shell       %zu voxels (S_n), %zu triangles\n", prepared.shell->voxels.size(),
                prepared.surface->triangles().size());
  std::printf("range       %.3f .. %.3f voxels\n", double(lo), double(hi));
  std::printf("time        read %.3f s, %s %.3f s, transform %.3f s (%d threads)\n", sec(t0, t1),
              o.init.c_str(), sec(t1, t2), sec(t2, t3),
              o.threads > 0 ? o.threads : core::default_threads());
  std::printf("wrote       %s\n", o.output.c_str());
  return 0;
}

}  // namespace

void add_distance_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<DistanceOptions>();
  CLI::App* cmd = app.add_subcommand(
      "distance", "Signed distance field of a volume's surface (float32, voxels, negative inside)");
  cmd->add_option("input", o->input, "uint8 density or float32 NRRD, or .vdb volume")
      ->check(input_file());
  cmd->add_option("-o,--output", o->output,
                  "output: float32 NRRD, or .vdb (level set and density)");
  cmd->add_option(
      "--method", o->method,
      "exact (default), brute, octree, chamfer-city, chamfer-345, chamfer-5x5x5, evdt, vcvdt");
  cmd->add_option("--init", o->init, "shell (sub-voxel, default) or binary");
  cmd->add_flag("--table", o->table, "print the §3.7 comparison (sphere and torus) as Markdown");
  cmd->add_option("--sizes", o->sizes, "--table sizes, comma separated (default 128,256)");
  cmd->add_option("--methods", o->methods,
                  "--table methods, comma separated (default all but brute)");
  add_threads_option(cmd, o->threads);
  cmd->callback([o, &action] { action = [o] { return run_distance(*o); }; });
}

}  // namespace sculpt::station::cli
