// sculpt stamp (IN.nrrd | --new NX,NY,NZ) --dabs DABS.jsonl -o OUT.nrrd
//
// Applies a dab script (project/dab_script.h: the format and its checks) to
// a volume. The tools the script saves and the volume appear together, or
// none of them if a line fails.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include <glm/vector_relational.hpp>

#include "cli/commands.h"
#include "cli/field_options.h"
#include "cli/number_checks.h"
#include "sculpt/base/output_set.h"
#include "sculpt/core/files/volume_file.h"
#include "sculpt/core/sculpt/sculptor.h"
#include "sculpt/core/sculpt/stroke.h"
#include "sculpt/core/tool/tool.h"
#include "sculpt/core/tool/tool_rotation.h"
#include "sculpt/core/tool/tool_scale.h"
#include "sculpt/core/volume/volume_io.h"
#include "sculpt/hal/stroke/stroke_sampler.h"
#include "sculpt/sim/session/command_limits.h"
#include "sculpt/sim/session/session.h"
#include "sculpt/station/app/station_loop.h"
#include "sculpt/station/project/dab_script.h"

namespace sculpt::station::cli {
namespace {

// The script's operations, as dab_script::read() gives them.
using namespace dab_script;  // NOLINT(google-build-using-namespace)

// A stroke line's samples: its points, or with a spacing, where the
// station's stroke sampler places them along the points' polyline (the
// first point, then one every spacing; the rest short of a spacing is
// dropped, as live input's is).
std::vector<core::StrokeSample> stroke_samples(const SweepOp& op) {
  if (op.spacing_vox <= 0.0) return op.path;
  hal::StrokeSampler sampler(1.0f, static_cast<float>(op.spacing_vox));
  std::vector<hal::Dab> dabs;
  for (size_t i = 0; i < op.path.size(); ++i) {
    const hal::ToolPose pose{op.path[i].position_vox, op.path[i].orientation,
                             static_cast<int64_t>(i)};
    i == 0 ? sampler.begin(pose, dabs) : sampler.add(pose, dabs);
  }
  sampler.end();
  std::vector<core::StrokeSample> out;
  out.reserve(dabs.size());
  for (const hal::Dab& d : dabs)
    out.push_back({d.position, d.orientation});
  return out;
}

// A brush line's stroke (the ball brushes need no tool): the voxels changed.
int64_t apply_brush(core::Volume& volume, core::Sculptor& sculptor, const BrushOp& op) {
  return std::visit(
      [&](const auto& o) -> int64_t {
        using O = std::decay_t<decltype(o)>;
        if constexpr (std::is_same_v<O, core::SmoothBrushOptions>)
          return core::smooth_stroke(volume, sculptor, op.path, o);
        else if constexpr (std::is_same_v<O, core::ClayBrushOptions>)
          return core::clay_stroke(volume, sculptor, op.path, o);
        else if constexpr (std::is_same_v<O, core::FlattenBrushOptions>)
          return core::flatten_stroke(volume, sculptor, op.path, o);
        else if constexpr (std::is_same_v<O, core::InflateBrushOptions>)
          return core::inflate_stroke(volume, sculptor, op.path, o);
        else if constexpr (std::is_same_v<O, core::PinchBrushOptions>)
          return core::pinch_stroke(volume, sculptor, op.path, o);
        else
          return core::grab_stroke(volume, sculptor, op.path, o);
      },
      op.options);
}

struct StampOptions {
  std::string input;
  std::vector<int> new_dims;
  std::string dabs;
  std::string output;
  DensityOptions density;
};

int run_stamp(const StampOptions& o) {
  if (o.input.empty() == o.new_dims.empty()) {
    return report(Error("give either an input volume or --new NX,NY,NZ"));
  }
  std::optional<core::Volume> volume;
  if (!o.new_dims.empty()) {
    const glm::ivec3 dims(o.new_dims[0], o.new_dims[1], o.new_dims[2]);
    if (Status st = core::Volume::validate(dims, {}); !st) return report(st.error().in("--new"));
    volume.emplace(dims, uint8_t{0});
  } else {
    const auto window = density_window(o.density, o.input);
    if (!window) return report(window.error());
    auto v = core::read_volume_file(o.input, {}, {}, window->has_value() ? &**window : nullptr);
    if (!v) return report(v.error());
    volume.emplace(std::move(v.value()));
  }

  // Read the whole script first: a bad line must not leave half a job done.
  auto script = dab_script::read(o.dabs, volume->dims());
  if (!script) return report(script.error());
  const std::filesystem::path script_dir = std::filesystem::path(o.dabs).parent_path();
  core::Sculptor sculptor(*volume);
  std::optional<core::Tool> tool;
  core::DabStats total;
  int dabs = 0;
  int strokes = 0;
  int64_t stroke_samples_total = 0;
  int brushes = 0;
  int64_t brush_voxels = 0;
  // The tools the script saves and the volume appear together, or none of
  // them if a later line fails.
  OutputSet outputs;
  const auto t0 = std::chrono::steady_clock::now();
  for (auto& [n, op] : *script) {
    const std::string where = o.dabs + ":" + std::to_string(n);
    if (auto* t = std::get_if<ToolOp>(&op)) {
      if (const auto shape = sim::parse_tool_shape(t->shape)) {
        tool = make_tool(*shape, static_cast<float>(t->a), static_cast<float>(t->b));
      }
      if (t->shape == "region") tool = core::tool_from_volume(*volume, t->box);
      if (t->shape == "file") {
        const std::filesystem::path p(t->path);
        auto loaded = core::read_tool_file(p.is_absolute() ? p : script_dir / p);
        if (!loaded) return report(loaded.error().in(where));
        if (glm::any(glm::greaterThan(loaded->density.dims(), glm::ivec3(kMaxToolEdge)))) {
          return report(
              Error("tool is larger than " + std::to_string(kMaxToolEdge) + " voxels on an edge")
                  .in(where));
        }
        tool = std::move(loaded.value());
      }
      if (t->hardness < 1.0)
        tool = core::with_hardness(std::move(*tool), static_cast<float>(t->hardness));
      if (t->scale != 1.0) {
        const auto factor = static_cast<float>(t->scale);
        if (glm::any(glm::greaterThan(core::scaled_tool_dims(tool->density.dims(), factor),
                                      glm::ivec3(kMaxToolEdge)))) {
          return report(Error("the scaled tool would be larger than " +
                              std::to_string(kMaxToolEdge) + " voxels on an edge")
                            .in(where));
        }
        tool = core::scale_tool(*tool, factor);
      }
      sculptor.set_tool(*tool);
    } else if (auto* s = std::get_if<SaveToolOp>(&op)) {
      if (!tool) return report(Error("save_tool before any tool").in(where));
      const std::filesystem::path p(s->path);
      if (Status st =
              core::write_tool_file(outputs.stage(p.is_absolute() ? p : script_dir / p), *tool);
          !st) {
        return report(outputs.named(st.error()).in(where));
      }
    } else if (auto* sm = std::get_if<SamplingOp>(&op)) {
      sculptor.set_sampling(sm->sampling);
    } else if (auto* m = std::get_if<MirrorOp>(&op)) {
      sculptor.set_mirror(m->plane);
    } else if (auto* st = std::get_if<StrokeOp>(&op)) {
      st->begin ? sculptor.begin_stroke() : sculptor.end_stroke();
    } else if (auto* u = std::get_if<UndoOp>(&op)) {
      const bool done = u->redo ? sculptor.redo() : sculptor.undo();
      if (!done)
        std::fprintf(stderr, "sculpt: %s: nothing to %s\n", where.c_str(),
                     u->redo ? "redo" : "undo");
    } else if (auto* d = std::get_if<core::Dab>(&op)) {
      if (!tool) return report(Error("dab before any tool").in(where));
      total += sculptor.dab(*d);
      ++dabs;
    } else if (auto* b = std::get_if<BrushOp>(&op)) {
      brush_voxels += apply_brush(*volume, sculptor, *b);
      ++brushes;
    } else if (auto* sw = std::get_if<SweepOp>(&op)) {
      if (!tool) return report(Error("stroke before any tool").in(where));
      const std::vector<core::StrokeSample> samples = stroke_samples(*sw);
      total += core::sweep_stroke(sculptor, samples, sw->options);
      ++strokes;
      stroke_samples_total += static_cast<int64_t>(samples.size());
    }
  }
  sculptor.end_stroke();
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (Status st = core::write_volume_file(outputs.stage(o.output), *volume); !st) {
    return report(outputs.named(st.error()));
  }
  if (Status st = outputs.commit(); !st) return report(st.error());

  std::printf("%d dabs in %.2f ms (%.3f ms per dab): %d bricks changed, %lld voxels changed\n",
              dabs, ms, dabs ? ms / dabs : 0.0, total.bricks_changed,
              static_cast<long long>(total.voxels_changed));
  if (strokes > 0) {
    std::printf("%d swept strokes through %lld samples\n", strokes,
                static_cast<long long>(stroke_samples_total));
  }
  if (brushes > 0) {
    std::printf("%d brush strokes: %lld voxels changed\n", brushes,
                static_cast<long long>(brush_voxels));
  }
  std::printf("time: decode %.2f ms, rotate on contact + combine %.2f ms, re-encode %.2f ms\n",
              static_cast<double>(total.decode_ns) * 1e-6,
              static_cast<double>(total.apply_ns) * 1e-6,
              static_cast<double>(total.encode_ns) * 1e-6);
  if (tool) {
    const core::RotatedToolCacheStats& c = sculptor.cache().stats();
    std::printf(
        "rotation cache (last tool): %lld of %lld placements hit, %.1f%% of %lld requested voxels "
        "reused, %zu "
        "bytes\n",
        static_cast<long long>(c.placement_hits), static_cast<long long>(c.placements),
        100.0 * c.voxel_hit_rate(), static_cast<long long>(c.voxels_requested), c.bytes);
  }
  std::printf("undo: %zu strokes (%zu bytes); wrote %s\n", sculptor.history().undo_depth(),
              sculptor.history().memory_bytes(), o.output.c_str());
  return 0;
}

}  // namespace

void add_stamp_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<StampOptions>();
  CLI::App* cmd =
      app.add_subcommand("stamp", "apply a JSON Lines script of tools and dabs to a volume");
  cmd->add_option("input", o->input,
                  "volume to sculpt: NRRD (uint8, or any type with --window) or .vdb")
      ->check(input_file());
  add_density_options(cmd, o->density);
  cmd->add_option("--new", o->new_dims, "start from an empty volume of NX,NY,NZ voxels")
      ->delimiter(',')
      ->expected(3);
  cmd->add_option("--dabs", o->dabs, "JSON Lines script (see docs/formats.md)")
      ->required()
      ->check(input_file());
  cmd->add_option("-o,--output", o->output, "output volume (.nrrd or .vdb)")->required();
  cmd->callback([o, &action] { action = [o] { return run_stamp(*o); }; });
}

}  // namespace sculpt::station::cli
