// sculpt haptics trace VOLUME.nrrd --probe PROBE.jsonl [--radius R] [--stiffness K]
//                      [--voxel-mm S] [--friction MUS,MUD] [--damping B] [--max-force F]
//                      -o TRACE.jsonl
//
// Runs the haptic tick (core/haptics) on a recorded or scripted device path
// and writes what the device would have felt, one line per probe line. The
// patch follows the proxy the way the sculpting thread keeps it centred for
// the 1 kHz loop (a re-centre between ticks once the proxy is edge/8 off), so
// the trace is the loop's output, bit for bit, whatever machine runs it.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "cli/commands.h"
#include "sculpt/core/haptics/distance_patch.h"
#include "sculpt/core/haptics/haptic_renderer.h"
#include "sculpt/core/haptics/probe_file.h"
#include "sculpt/core/io/atomic_file.h"
#include "sculpt/core/io/nrrd.h"

namespace sculpt::station::cli {
namespace {

struct TraceOptions {
  std::string volume, probe, output;
  float radius_vox = 1.0f;
  float stiffness_n_per_mm = 1.0f;
  float voxel_mm = 0.5f;
  std::vector<float> friction;  // static, dynamic
  float damping_ns_per_m = 0.0f;
  float max_force_n = 8.0f;
};

// CLI::Range lets NaN through (every comparison with it is false).
CLI::Validator finite_range(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& text) -> std::string {
        double v = 0.0;
        if (!CLI::detail::lexical_cast(text, v) || !std::isfinite(v) || v < lo || v > hi)
          return "value " + text + " not a number in [" + std::to_string(lo) + ", " +
                 std::to_string(hi) + "]";
        return {};
      },
      "FINITE in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

int run_trace(const TraceOptions& o) {
  auto density = core::read_nrrd_u8(o.volume);
  if (!density) return report(density.error());
  const core::Status valid = core::Volume::validate(density->dims(), {});
  if (!valid) return report(valid.error().in(o.volume));
  auto probe = core::read_probe_file(o.probe);
  if (!probe) return report(probe.error());
  if (!o.friction.empty() && o.friction[1] > o.friction[0])
    return report(core::Error("--friction: the dynamic coefficient " +
                              std::to_string(o.friction[1]) + " exceeds the static one " +
                              std::to_string(o.friction[0])));

  const core::Volume volume = core::Volume::from_dense(*density);
  core::HapticSettings settings;
  settings.proxy.radius_vox = o.radius_vox;
  if (!o.friction.empty()) settings.proxy.friction = {o.friction[0], o.friction[1]};
  settings.coupling.stiffness_n_per_mm = o.stiffness_n_per_mm;
  settings.coupling.voxel_mm = o.voxel_mm;
  settings.coupling.damping_ns_per_m = o.damping_ns_per_m;
  settings.coupling.max_force_n = o.max_force_n;
  // The band must reach the sphere's radius and a little beyond, so that
  // phi - r is exact where the proxy rests.
  const float band_vox = std::max(4.0f, std::ceil(o.radius_vox) + 2.0f);
  core::DistancePatch patch({core::patch_edge_for_reach(o.radius_vox, band_vox), band_vox});
  core::HapticRenderer renderer(settings);

  patch.build(volume, probe->front().at_vox);
  std::string text;
  int64_t contact_ticks = 0;
  float max_force = 0.0f, deepest = 0.0f;
  for (const core::ProbeSample& sample : *probe) {
    const core::HapticTick& tick = renderer.tick(patch.snapshot(), sample.at_vox, sample.t_s);
    const glm::vec3 proxy = tick.proxy.position_vox;
    core::TraceLine line;
    line.t_s = sample.t_s;
    line.device_vox = sample.at_vox;
    line.proxy_vox = proxy;
    line.force_n = tick.force_n;
    line.contact = tick.proxy.contact;
    text += core::format_trace_line(line);
    contact_ticks += tick.proxy.contact;
    max_force = std::max(max_force, glm::length(tick.force_n));
    deepest = std::min(deepest, patch.snapshot().sample(proxy).phi_vox - o.radius_vox);
    if (patch.off_centre(proxy) || tick.proxy.at_patch_edge) patch.recentre(volume, proxy);
  }
  core::AtomicFileWriter out(o.output);
  if (!out.ok()) return report(out.error());
  out.write(text);
  const core::Status st = out.commit();
  if (!st) return report(st.error());
  std::printf(
      "trace       %zu ticks, %lld in contact, max force %.3f N, deepest proxy %.3f voxels\n",
      probe->size(), static_cast<long long>(contact_ticks), double(max_force), double(-deepest));
  std::printf("wrote       %s\n", o.output.c_str());
  return 0;
}

}  // namespace

void add_haptics_command(CLI::App& app, Action& action) {
  CLI::App* haptics = app.add_subcommand("haptics", "Haptic contact on the material");
  haptics->require_subcommand(1);
  auto o = std::make_shared<TraceOptions>();
  CLI::App* cmd = haptics->add_subcommand(
      "trace", "Run the haptic tick along a device path and write the force at each step");
  cmd->add_option("volume", o->volume, "uint8 density NRRD")->required();
  cmd->add_option("--probe", o->probe, "device path: JSON Lines {\"t\": s, \"at\": [x, y, z]}")
      ->required();
  cmd->add_option("-o,--output", o->output, "trace, JSON Lines")->required();
  cmd->add_option("--radius", o->radius_vox, "sphere tool radius, voxels (0: a point)")
      ->check(finite_range(0.0, 32.0));
  cmd->add_option("--stiffness", o->stiffness_n_per_mm, "coupling stiffness K, N/mm")
      ->check(finite_range(1e-3, 100.0));
  cmd->add_option("--voxel-mm", o->voxel_mm, "voxel size S, mm")->check(finite_range(1e-3, 100.0));
  cmd->add_option("--friction", o->friction, "static,dynamic Coulomb coefficients")
      ->delimiter(',')
      ->expected(2)
      ->check(finite_range(0.0, 10.0));
  cmd->add_option("--damping", o->damping_ns_per_m, "damping along the normal B, N*s/m")
      ->check(finite_range(0.0, 1000.0));
  cmd->add_option("--max-force", o->max_force_n, "force limit F, N")
      ->check(finite_range(1e-3, 1000.0));
  cmd->callback([o, &action] { action = [o] { return run_trace(*o); }; });
}

}  // namespace sculpt::station::cli
