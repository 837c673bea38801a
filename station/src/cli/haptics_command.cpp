// sculpt haptics trace VOLUME.nrrd --probe PROBE.jsonl [--radius R] [--stiffness K]
//                      [--voxel-mm S] [--friction MUS,MUD] [--damping B] [--max-force F]
//                      [--tool SPEC] [--carve add|subtract [--press-threshold N]
//                      [--press-depth VOX_PER_N] [--carved OUT.nrrd]] -o TRACE.jsonl
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
#include <optional>
#include <vector>

#include "cli/commands.h"
#include "cli/field_options.h"
#include "cli/number_checks.h"
#include "sculpt/base/atomic_file.h"
#include "sculpt/core/files/volume_file.h"
#include "sculpt/core/haptics/distance_patch.h"
#include "sculpt/core/haptics/haptic_renderer.h"
#include "sculpt/core/haptics/press_dab.h"
#include "sculpt/core/haptics/probe_file.h"
#include "sculpt/core/haptics/tool_proxy.h"
#include "sculpt/core/io/nrrd.h"
#include "sculpt/core/sculpt/sculptor.h"

namespace sculpt::station::cli {
namespace {

struct TraceOptions {
  std::string volume, probe, output;
  DensityOptions density;
  float radius_vox = 1.0f;
  float stiffness_n_per_mm = 1.0f;
  float voxel_mm = 0.5f;
  std::vector<float> friction;  // static, dynamic
  float damping_ns_per_m = 0.0f;
  float max_force_n = 8.0f;
  std::string tool;   // empty: a sphere of radius_vox
  std::string carve;  // empty: touch only
  float press_threshold_n = 1.0f;
  float press_depth_vox_per_n = 1.0f;
  std::string carved;  // write the carved volume here
};

// sphere:R, cube:E, cylinder:R,H, ring:R,r, cone:R,H (voxels), or a tool NRRD.
Result<core::Tool> tool_from_spec(const std::string& spec) {
  const size_t colon = spec.find(':');
  const std::string shape = spec.substr(0, colon);
  if (colon == std::string::npos) {
    auto tool = core::read_tool_file(spec);
    if (!tool) return tool.error();
    return std::move(tool).value();
  }
  std::vector<float> sizes;
  std::string rest = spec.substr(colon + 1);
  for (size_t at = 0; at <= rest.size();) {
    const size_t comma = std::min(rest.find(',', at), rest.size());
    double v = 0.0;
    const std::string word = rest.substr(at, comma - at);
    if (!CLI::detail::lexical_cast(word, v) || !std::isfinite(v) || v < 0.5 || v > 64.0)
      return Error("--tool " + spec + ": '" + word + "' is not a size in [0.5, 64] voxels");
    sizes.push_back(float(v));
    at = comma + 1;
  }
  const auto want = [&](size_t n) -> Status {
    if (sizes.size() == n) return {};
    return Error("--tool " + spec + ": " + shape + " takes " + std::to_string(n) + " size(s)");
  };
  Status st;
  if (shape == "sphere" && (st = want(1))) return core::make_sphere_tool(sizes[0]);
  if (shape == "cube" && (st = want(1))) return core::make_cube_tool(sizes[0]);
  if (shape == "cylinder" && (st = want(2))) return core::make_cylinder_tool(sizes[0], sizes[1]);
  if (shape == "ring" && (st = want(2))) return core::make_ring_tool(sizes[0], sizes[1]);
  if (shape == "cone" && (st = want(2))) return core::make_cone_tool(sizes[0], sizes[1]);
  if (!st) return st.error();
  return Error("--tool " + spec + ": unknown shape '" + shape +
               "' (sphere, cube, cylinder, ring, cone, or a tool NRRD)");
}

int run_trace(const TraceOptions& o) {
  const auto window = density_window(o.density, o.volume);
  if (!window) return report(window.error());
  auto density = core::read_density_file(o.volume, window->has_value() ? &**window : nullptr);
  if (!density) return report(density.error());
  const Status valid = core::Volume::validate(density->dims(), {});
  if (!valid) return report(valid.error().in(o.volume));
  auto probe = core::read_probe_file(o.probe);
  if (!probe) return report(probe.error());
  if (!o.friction.empty() && o.friction[1] > o.friction[0])
    return report(Error("--friction: the dynamic coefficient " + std::to_string(o.friction[1]) +
                        " exceeds the static one " + std::to_string(o.friction[0])));

  std::optional<core::Tool> tool;
  if (!o.tool.empty()) {
    auto t = tool_from_spec(o.tool);
    if (!t) return report(t.error());
    tool = std::move(t).value();
  }
  std::optional<core::SculptMode> carve;
  if (!o.carve.empty()) carve = core::parse_sculpt_mode(o.carve);

  core::Volume volume = core::Volume::from_dense(*density);
  core::HapticSettings settings;
  settings.proxy.radius_vox = o.radius_vox;
  if (!o.friction.empty()) settings.proxy.friction = {o.friction[0], o.friction[1]};
  settings.coupling.stiffness_n_per_mm = o.stiffness_n_per_mm;
  settings.coupling.voxel_mm = o.voxel_mm;
  settings.coupling.damping_ns_per_m = o.damping_ns_per_m;
  settings.coupling.max_force_n = o.max_force_n;
  core::ToolProxyOptions tool_options;
  tool_options.stiffness_n_per_mm = o.stiffness_n_per_mm;
  tool_options.voxel_mm = o.voxel_mm;
  tool_options.max_force_n = o.max_force_n;
  std::optional<core::ToolProxy> tool_proxy;
  if (tool) tool_proxy.emplace(core::make_point_shell(*tool), tool_options);
  // The band must reach the sphere's radius and a little beyond, so that
  // phi - r is exact where the proxy rests; a tool's shell samples phi < 0.
  const float reach_vox = tool_proxy ? tool_proxy->shell().reach_vox : o.radius_vox;
  const float band_vox = tool_proxy ? 4.0f : core::band_for_sphere(o.radius_vox);
  core::DistancePatch patch({core::patch_edge_for_reach(reach_vox, band_vox), band_vox});
  core::HapticRenderer renderer(settings);
  std::optional<core::Sculptor> sculptor;
  if (carve) {
    sculptor.emplace(volume);
    sculptor->set_tool(tool ? *tool : core::make_sphere_tool(std::max(o.radius_vox, 1.0f)));
  }
  const core::PressOptions press{o.press_threshold_n, o.press_depth_vox_per_n, 4.0f};

  patch.build(volume, probe->front().at_vox);
  (void)volume.take_dirty_bricks();
  std::string text;
  int64_t contact_ticks = 0, dabs = 0;
  float max_force = 0.0f;
  for (const core::ProbeSample& sample : *probe) {
    const glm::quat device_orientation = sample.orientation.value_or(glm::quat(1, 0, 0, 0));
    core::TraceLine line;
    line.t_s = sample.t_s;
    line.device_vox = sample.at_vox;
    glm::vec3 normal(0.0f);
    glm::quat orientation = device_orientation;
    if (tool_proxy) {
      const core::ToolTick& tick =
          tool_proxy->update(patch.snapshot(), sample.at_vox, device_orientation);
      line.proxy_vox = tick.position_vox;
      line.force_n = tick.force_n;
      line.torque_nm = tick.torque_nm;
      line.contact = tick.contact;
      orientation = tick.orientation;
      const float f = glm::length(tick.force_n);
      if (f > 0.0f) normal = tick.force_n / f;
    } else {
      const core::HapticTick& tick = renderer.tick(patch.snapshot(), sample.at_vox, sample.t_s);
      line.proxy_vox = tick.proxy.position_vox;
      line.force_n = tick.force_n;
      line.contact = tick.proxy.contact;
      normal = tick.proxy.normal;
    }
    if (!core::trace_line_finite(line)) {
      return report(Error(o.output + ": tick " + std::to_string(&sample - &probe->front()) +
                          " has a value that is not a finite number; nothing written"));
    }
    text += core::format_trace_line(line);
    contact_ticks += line.contact;
    max_force = std::max(max_force, glm::length(line.force_n));
    // The sculpting side, between ticks: a pressed dab, then the patch
    // refreshed where it changed and moved when the proxy has drifted.
    if (sculptor) {
      if (const auto at = core::pressed_dab_position(line.proxy_vox, normal, line.force_n,
                                                     line.contact, press)) {
        core::Dab dab;
        dab.position_vox = *at;
        dab.orientation = orientation;
        dab.mode = *carve;
        (void)sculptor->dab(dab);
        ++dabs;
        patch.refresh_bricks(volume, volume.take_dirty_bricks());
      }
    }
    if (patch.off_centre(line.proxy_vox)) patch.recentre(volume, line.proxy_vox);
  }
  // The trace's temporary file first: an unwritable output fails before the
  // carved volume is written.
  AtomicFileWriter out(o.output);
  if (!out.ok()) return report(out.error());
  out.write(text);
  if (!o.carved.empty()) {
    const Status carved = core::write_density_file(o.carved, volume.to_dense());
    if (!carved) return report(carved.error());
  }
  const Status st = out.commit();
  if (!st) return report(st.error());
  std::printf("trace       %zu ticks, %lld in contact, max force %.3f N, %lld dabs\n",
              probe->size(), static_cast<long long>(contact_ticks), double(max_force),
              static_cast<long long>(dabs));
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
  cmd->add_option("volume", o->volume, "density: NRRD (uint8, or any type with --window) or .vdb")
      ->required()
      ->check(input_file());
  add_density_options(cmd, o->density);
  cmd->add_option("--probe", o->probe, "device path: JSON Lines {\"t\": s, \"at\": [x, y, z]}")
      ->required()
      ->check(input_file());
  cmd->add_option("-o,--output", o->output, "trace, JSON Lines")->required();
  // Beyond 8 voxels the sphere's band makes the patch slow to build: larger
  // tools take --tool's point shell.
  cmd->add_option("--radius", o->radius_vox, "sphere tool radius, voxels (0: a point)")
      ->check(finite_range(0.0, 8.0));
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
  cmd->add_option("--tool", o->tool,
                  "tool-shaped contact with torque: sphere:R, cube:E, cylinder:R,H, ring:R,r, "
                  "cone:R,H (voxels) or a tool NRRD");
  cmd->add_option("--carve", o->carve, "carve where the tool is pushed in: add or subtract")
      ->check(CLI::IsMember({"add", "subtract"}));
  cmd->add_option("--press-threshold", o->press_threshold_n, "push that starts carving, N")
      ->check(finite_range(0.0, 1000.0));
  cmd->add_option("--press-depth", o->press_depth_vox_per_n, "carving depth per newton, voxels/N")
      ->check(finite_range(0.0, 100.0));
  cmd->add_option("--carved", o->carved, "write the carved volume (uint8 NRRD, or .vdb)");
  cmd->callback([o, &action] { action = [o] { return run_trace(*o); }; });
}

}  // namespace sculpt::station::cli
