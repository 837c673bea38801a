// sculpt stamp (IN.nrrd | --new NX,NY,NZ) --dabs DABS.jsonl -o OUT.nrrd
//
// Applies a script of sculpting operations to a volume: the scripting face of
// the discrete tools ("Discrete tools for virtual sculpture" §3). The script
// is JSON Lines, one object per line, each with an "op" (blank lines and
// lines starting with '#' are skipped):
//   {"op":"tool","shape":"sphere","radius":8}        also cube (edge), cylinder
//   (radius, height), ring (major, minor), cone (radius, height),
//   file (path, relative to the script), region (box [x0,y0,z0,x1,y1,z1] of
//   the volume as it is now: the sculpture becomes the tool)
//   {"op":"save_tool","path":"t.nrrd"}               the current tool, with pivot
//   {"op":"sampling","value":"trilinear"}            or "nearest"
//   {"op":"mirror","axis":"x","centre":63.5}         axis "off" disables
//   {"op":"begin"} ... {"op":"end"}                  a stroke (one undo step)
//   {"op":"dab","at":[x,y,z],"mode":"add","strength":1,"euler":[rx,ry,rz]}
//        mode add|subtract|union|difference|smooth (default add), strength in
//        [0, 1] (default 1), rotation as "euler" (degrees, extrinsic xyz) or
//        "quat" [w,x,y,z] (default none)
//   {"op":"undo"}, {"op":"redo"}
// Every line is checked before the volume is touched; an error names the
// script, the line and the field, and nothing is written.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <glm/vector_relational.hpp>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "sculpt/base/output_set.h"
#include "sculpt/core/sculpt/sculptor.h"
#include "sculpt/core/tool/tool.h"
#include "sculpt/core/tool/tool_rotation.h"
#include "sculpt/core/volume/volume_io.h"
#include "sculpt/sim/session/session.h"
#include "sculpt/station/app/station_loop.h"

namespace sculpt::station::cli {
namespace {

using json = nlohmann::json;

/// Largest built-in tool size accepted, in voxels (a 1024^3 tool grid).
constexpr double kMaxToolSize = 500.0;

/// Largest tool grid edge accepted from a file or a region, in voxels: the
/// rotation cache indexes rows with 16-bit offsets, and a tool that large
/// would be a volume, not a tool.
constexpr int kMaxToolEdge = 1024;

struct StampOptions {
  std::string input;
  std::vector<int> new_dims;
  std::string dabs;
  std::string output;
};

struct ToolOp {
  std::string shape;
  double a = 0.0, b = 0.0;
  std::string path;
  core::Box box;
};
struct SaveToolOp {
  std::string path;
};
struct SamplingOp {
  core::Sampling sampling;
};
struct MirrorOp {
  std::optional<core::MirrorPlane> plane;
};
struct StrokeOp {
  bool begin;
};
struct UndoOp {
  bool redo;
};
using Op = std::variant<ToolOp, SaveToolOp, SamplingOp, MirrorOp, StrokeOp, core::Dab, UndoOp>;

// Reads field `key` of `j` as a finite number.
Result<double> number(const json& j, const char* key) {
  if (!j.contains(key)) return Error(std::string("missing '") + key + "'");
  const json& v = j[key];
  if (!v.is_number() || !std::isfinite(v.get<double>())) {
    return Error(std::string("'") + key + "' must be a finite number");
  }
  return v.get<double>();
}

Result<double> size(const json& j, const char* key) {
  auto v = number(j, key);
  if (!v) return v;
  if (*v <= 0.0 || *v > kMaxToolSize) {
    return Error(std::string("'") + key + "' must be in (0, " +
                       std::to_string(int(kMaxToolSize)) + "]");
  }
  return v;
}

Result<std::vector<double>> numbers(const json& j, const char* key, size_t n) {
  const std::string what =
      std::string("'") + key + "' must be " + std::to_string(n) + " finite numbers";
  if (!j.contains(key) || !j[key].is_array() || j[key].size() != n) return Error(what);
  std::vector<double> out;
  for (const json& v : j[key]) {
    if (!v.is_number() || !std::isfinite(v.get<double>())) return Error(what);
    out.push_back(v.get<double>());
  }
  return out;
}

Result<Op> parse_op(const json& j, glm::ivec3 dims) {
  if (!j.is_object() || !j.contains("op") || !j["op"].is_string()) {
    return Error("expected an object with a string 'op'");
  }
  const std::string op = j["op"];
  if (op == "tool") {
    if (!j.contains("shape") || !j["shape"].is_string())
      return Error("tool: missing string 'shape'");
    ToolOp t{j["shape"], 0.0, 0.0, {}, {}};
    const std::pair<const char*, const char*> params[] = {{"sphere", "radius"},
                                                          {"cube", "edge"},
                                                          {"cylinder", "radius"},
                                                          {"ring", "major"},
                                                          {"cone", "radius"}};
    for (const auto& [shape, first] : params) {
      if (t.shape != shape) continue;
      auto a = size(j, first);
      if (!a) return a.error().in("tool " + t.shape);
      t.a = *a;
      const char* second = t.shape == "ring"                              ? "minor"
                           : (t.shape == "cylinder" || t.shape == "cone") ? "height"
                                                                          : nullptr;
      if (second != nullptr) {
        auto b = size(j, second);
        if (!b) return b.error().in("tool " + t.shape);
        t.b = *b;
      }
      return Op{t};
    }
    if (t.shape == "file") {
      if (!j.contains("path") || !j["path"].is_string())
        return Error("tool file: missing string 'path'");
      t.path = j["path"];
      return Op{t};
    }
    if (t.shape == "region") {
      auto b = numbers(j, "box", 6);
      if (!b) return b.error().in("tool region");
      const std::vector<double>& v = *b;
      t.box = core::Box{glm::ivec3(int(v[0]), int(v[1]), int(v[2])),
                        glm::ivec3(int(v[3]), int(v[4]), int(v[5]))};
      const core::Box clipped = core::intersect(t.box, core::Box{glm::ivec3(0), dims});
      if (clipped.empty() || clipped != t.box) {
        return Error("tool region: 'box' must be a non-empty box inside the volume");
      }
      if (glm::any(glm::greaterThan(t.box.size(), glm::ivec3(kMaxToolEdge)))) {
        return Error("tool region: 'box' is larger than " + std::to_string(kMaxToolEdge) +
                           " voxels on an edge");
      }
      for (double x : v) {
        if (x != std::floor(x))
          return Error("tool region: 'box' must be whole voxel indices");
      }
      return Op{t};
    }
    return Error("tool: unknown shape '" + t.shape +
                       "' (sphere, cube, cylinder, ring, cone, file, region)");
  }
  if (op == "save_tool") {
    if (!j.contains("path") || !j["path"].is_string())
      return Error("save_tool: missing string 'path'");
    return Op{SaveToolOp{j["path"]}};
  }
  if (op == "sampling") {
    const std::string v = j.value("value", "");
    if (v == "nearest") return Op{SamplingOp{core::Sampling::kNearest}};
    if (v == "trilinear") return Op{SamplingOp{core::Sampling::kTrilinear}};
    return Error("sampling: 'value' must be \"nearest\" or \"trilinear\"");
  }
  if (op == "mirror") {
    const std::string axis = j.value("axis", "");
    if (axis == "off") return Op{MirrorOp{std::nullopt}};
    if (axis != "x" && axis != "y" && axis != "z")
      return Error("mirror: 'axis' must be x, y, z or off");
    auto c = number(j, "centre");
    if (!c) return c.error().in("mirror");
    return Op{MirrorOp{core::MirrorPlane{axis[0] - 'x', static_cast<float>(*c)}}};
  }
  if (op == "begin" || op == "end") return Op{StrokeOp{op == "begin"}};
  if (op == "undo" || op == "redo") return Op{UndoOp{op == "redo"}};
  if (op == "dab") {
    core::Dab d;
    auto at = numbers(j, "at", 3);
    if (!at) return at.error().in("dab");
    d.position_vox = glm::vec3((*at)[0], (*at)[1], (*at)[2]);
    const std::string mode = j.value("mode", "add");
    const auto m = core::parse_sculpt_mode(mode);
    if (!m)
      return Error("dab: unknown mode '" + mode +
                         "' (add, subtract, union, difference, smooth)");
    d.mode = *m;
    if (j.contains("strength")) {
      auto s = number(j, "strength");
      if (!s || *s < 0.0 || *s > 1.0)
        return Error("dab: 'strength' must be a number in [0, 1]");
      d.strength = static_cast<float>(*s);
    }
    if (j.contains("euler") && j.contains("quat"))
      return Error("dab: give 'euler' or 'quat', not both");
    if (j.contains("euler")) {
      auto e = numbers(j, "euler", 3);
      if (!e) return e.error().in("dab");
      d.orientation = glm::quat_cast(core::euler_xyz_deg(glm::vec3((*e)[0], (*e)[1], (*e)[2])));
    } else if (j.contains("quat")) {
      auto q = numbers(j, "quat", 4);
      if (!q) return q.error().in("dab");
      const glm::quat qq(static_cast<float>((*q)[0]), static_cast<float>((*q)[1]),
                         static_cast<float>((*q)[2]), static_cast<float>((*q)[3]));
      if (!(glm::length(qq) > 1e-6f)) return Error("dab: 'quat' must not be zero");
      d.orientation = glm::normalize(qq);
    }
    return Op{d};
  }
  return Error("unknown op '" + op + "'");
}

int run_stamp(const StampOptions& o) {
  if (o.input.empty() == o.new_dims.empty()) {
    return report(Error("give either an input volume or --new NX,NY,NZ"));
  }
  std::optional<core::Volume> volume;
  if (!o.new_dims.empty()) {
    const glm::ivec3 dims(o.new_dims[0], o.new_dims[1], o.new_dims[2]);
    if (Status st = core::Volume::validate(dims, {}); !st)
      return report(st.error().in("--new"));
    volume.emplace(dims, uint8_t{0});
  } else {
    auto v = core::read_volume_nrrd(o.input);
    if (!v) return report(v.error());
    volume.emplace(std::move(v.value()));
  }

  // Parse the whole script first: a bad line must not leave half a job done.
  std::ifstream in(o.dabs, std::ios::binary);
  if (!in) return report(Error("cannot open the dab script").in(o.dabs));
  std::vector<std::pair<int, Op>> ops;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    const json j = json::parse(line, nullptr, false);
    if (j.is_discarded())
      return report(Error("not valid JSON").in(o.dabs + ":" + std::to_string(n)));
    auto op = parse_op(j, volume->dims());
    if (!op) return report(op.error().in(o.dabs + ":" + std::to_string(n)));
    ops.emplace_back(n, std::move(op.value()));
  }
  if (in.bad()) return report(Error("read error").in(o.dabs));

  const std::filesystem::path script_dir = std::filesystem::path(o.dabs).parent_path();
  core::Sculptor sculptor(*volume);
  std::optional<core::Tool> tool;
  core::DabStats total;
  int dabs = 0;
  // The tools the script saves and the volume appear together, or none of
  // them if a later line fails.
  OutputSet outputs;
  const auto t0 = std::chrono::steady_clock::now();
  for (auto& [n, op] : ops) {
    const std::string where = o.dabs + ":" + std::to_string(n);
    if (auto* t = std::get_if<ToolOp>(&op)) {
      if (const auto shape = sim::parse_tool_shape(t->shape)) {
        tool = make_tool(*shape, static_cast<float>(t->a), static_cast<float>(t->b));
      }
      if (t->shape == "region") tool = core::tool_from_volume(*volume, t->box);
      if (t->shape == "file") {
        const std::filesystem::path p(t->path);
        auto loaded = core::read_tool_nrrd(p.is_absolute() ? p : script_dir / p);
        if (!loaded) return report(loaded.error().in(where));
        if (glm::any(glm::greaterThan(loaded->density.dims(), glm::ivec3(kMaxToolEdge)))) {
          return report(Error("tool is larger than " + std::to_string(kMaxToolEdge) +
                                    " voxels on an edge")
                            .in(where));
        }
        tool = std::move(loaded.value());
      }
      sculptor.set_tool(*tool);
    } else if (auto* s = std::get_if<SaveToolOp>(&op)) {
      if (!tool) return report(Error("save_tool before any tool").in(where));
      const std::filesystem::path p(s->path);
      if (Status st =
              core::write_tool_nrrd(outputs.stage(p.is_absolute() ? p : script_dir / p), *tool);
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
    }
  }
  sculptor.end_stroke();
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (Status st = core::write_volume_nrrd(outputs.stage(o.output), *volume); !st) {
    return report(outputs.named(st.error()));
  }
  if (Status st = outputs.commit(); !st) return report(st.error());

  std::printf("%d dabs in %.2f ms (%.3f ms per dab): %d bricks changed, %lld voxels changed\n",
              dabs, ms, dabs ? ms / dabs : 0.0, total.bricks_changed,
              static_cast<long long>(total.voxels_changed));
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
  cmd->add_option("input", o->input, "uint8 NRRD volume to sculpt");
  cmd->add_option("--new", o->new_dims, "start from an empty volume of NX,NY,NZ voxels")
      ->delimiter(',')
      ->expected(3);
  cmd->add_option("--dabs", o->dabs, "JSON Lines script (see the README)")->required();
  cmd->add_option("-o,--output", o->output, "output NRRD volume")->required();
  cmd->callback([o, &action] { action = [o] { return run_stamp(*o); }; });
}

}  // namespace sculpt::station::cli
