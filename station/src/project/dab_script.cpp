#include "sculpt/station/project/dab_script.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <type_traits>
#include <utility>

#include <glm/gtc/quaternion.hpp>
#include <glm/vector_relational.hpp>
#include <nlohmann/json.hpp>

#include "sculpt/base/input_file.h"
#include "sculpt/core/tool/tool_scale.h"

#include "sculpt/sim/session/session.h"

namespace sculpt::station::dab_script {
namespace {

using json = nlohmann::json;

// Reads optional string field `key` of `j`, `fallback` when absent; an error
// in our words when present but not a string (json::value() would throw the
// library's own message, naming no line).
Result<std::string> text(const json& j, const char* key, const char* fallback) {
  if (!j.contains(key)) return std::string(fallback);
  if (!j[key].is_string()) return Error(std::string("'") + key + "' must be a string");
  return j[key].get<std::string>();
}

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
    return Error(std::string("'") + key + "' must be in (0, " + std::to_string(int(kMaxToolSize)) +
                 "]");
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

// Reads the optional "hardness" of a tool line into t.
Status read_hardness(const json& j, ToolOp& t) {
  if (!j.contains("hardness")) return {};
  auto h = number(j, "hardness");
  if (!h) return h.error().in("tool " + t.shape);
  if (Status st = core::check_hardness(*h); !st) return st.error().in("tool " + t.shape);
  t.hardness = *h;
  return {};
}

Status read_scale(const json& j, ToolOp& t) {
  if (!j.contains("scale")) return {};
  auto s = number(j, "scale");
  if (!s) return s.error().in("tool " + t.shape);
  if (*s < core::kMinToolScale || *s > core::kMaxToolScale) {
    return Error("'scale' must be in [0.125, 8]").in("tool " + t.shape);
  }
  t.scale = *s;
  return {};
}

// A point of a dab or stroke: a tool reaches at most its size past the
// volume, so a point farther out changes nothing, and one at 1e30 would only
// lose float precision.
Status check_point(const double* p, glm::ivec3 dims, const std::string& what) {
  const double margin = kMaxToolSize + 1.0;
  for (int a = 0; a < 3; ++a) {
    if (p[a] < -margin || p[a] > dims[a] + margin)
      return Error(what + " is more than " + std::to_string(int(margin)) +
                   " voxels outside the volume");
  }
  return {};
}

// The "path" of a stroke or brush line `op`: 1 to kMaxStrokePoints points,
// each checked by check_point().
Result<std::vector<core::StrokeSample>> read_path(const json& j, glm::ivec3 dims,
                                                  const std::string& op) {
  const std::string bad_path = op + ": 'path' must be a non-empty array of [x, y, z] points";
  if (!j.contains("path") || !j["path"].is_array() || j["path"].empty()) return Error(bad_path);
  const json& path = j["path"];
  if (path.size() > kMaxStrokePoints) {
    return Error(op + ": 'path' has more than " + std::to_string(kMaxStrokePoints) + " points");
  }
  std::vector<core::StrokeSample> out;
  for (size_t i = 0; i < path.size(); ++i) {
    const json& p = path[i];
    if (!p.is_array() || p.size() != 3) return Error(bad_path);
    double v[3];
    for (int a = 0; a < 3; ++a) {
      if (!p[a].is_number() || !std::isfinite(p[a].get<double>())) {
        return Error(op + ": 'path' point " + std::to_string(i) + " must be 3 finite numbers");
      }
      v[a] = p[a].get<double>();
    }
    if (Status st = check_point(v, dims, "'path' point " + std::to_string(i)); !st)
      return st.error().in(op);
    core::StrokeSample sample;
    sample.position_vox = glm::vec3(v[0], v[1], v[2]);
    out.push_back(sample);
  }
  return out;
}

Result<Op> parse_stroke(const json& j, glm::ivec3 dims) {
  SweepOp s;
  auto read = read_path(j, dims, "stroke");
  if (!read) return read.error();
  s.path = std::move(read.value());
  const json& path = j["path"];
  if (j.contains("quats")) {
    const json& quats = j["quats"];
    if (!quats.is_array() || quats.size() != path.size())
      return Error("stroke: 'quats' must hold one [w, x, y, z] per 'path' point");
    for (size_t i = 0; i < quats.size(); ++i) {
      const json& q = quats[i];
      const std::string what = "stroke: 'quats' entry " + std::to_string(i);
      if (!q.is_array() || q.size() != 4) return Error(what + " must be 4 finite numbers");
      float c[4];
      for (int a = 0; a < 4; ++a) {
        if (!q[a].is_number() || !std::isfinite(q[a].get<double>()))
          return Error(what + " must be 4 finite numbers");
        c[a] = static_cast<float>(q[a].get<double>());
      }
      const glm::quat qq(c[0], c[1], c[2], c[3]);
      if (!(glm::length(qq) > 1e-6f)) return Error(what + " must not be zero");
      s.path[i].orientation = glm::normalize(qq);
    }
  }
  const Result<std::string> mode_text = text(j, "mode", "add");
  if (!mode_text) return mode_text.error().in("stroke");
  const auto m = core::parse_sculpt_mode(*mode_text);
  if (!m || *m == core::SculptMode::kSmooth) {
    return Error("stroke: unknown mode '" + *mode_text +
                 "' (add, subtract, union, difference; to smooth, the \"smooth\" op)");
  }
  s.options.mode = *m;
  if (j.contains("strength")) {
    auto st = number(j, "strength");
    if (!st || *st < 0.0 || *st > 1.0)
      return Error("stroke: 'strength' must be a number in [0, 1]");
    s.options.strength = static_cast<float>(*st);
  }
  if (j.contains("accumulate")) {
    if (!j["accumulate"].is_boolean()) return Error("stroke: 'accumulate' must be true or false");
    s.options.accumulate = j["accumulate"].get<bool>();
  }
  if (j.contains("spacing")) {
    auto sp = number(j, "spacing");
    if (!sp || !(*sp > 0.0)) return Error("stroke: 'spacing' must be a number above 0 (voxels)");
    double length = 0.0;
    for (size_t i = 1; i < s.path.size(); ++i)
      length += glm::length(glm::dvec3(s.path[i].position_vox - s.path[i - 1].position_vox));
    if (length / *sp > kMaxStrokeSamples) {
      return Error("stroke: 'spacing' places more than " +
                   std::to_string(static_cast<int64_t>(kMaxStrokeSamples)) +
                   " samples on the path");
    }
    s.spacing_vox = *sp;
  }
  return Op{std::move(s)};
}

// A ball brush's line: "op" `name`, its "path", and the keys that set its
// options (`keys`, each read by `set` as a finite number, "passes" as a
// whole one), any other key refused; then the brush's own check.
template <class Options>
Result<Op> parse_brush(const json& j, glm::ivec3 dims, const std::string& name,
                       std::initializer_list<std::pair<const char*, float Options::*>> keys,
                       Status (*check)(const Options&)) {
  BrushOp b;
  auto path = read_path(j, dims, name);
  if (!path) return path.error();
  b.path = std::move(path.value());
  Options o;
  for (const auto& item : j.items()) {
    const std::string& key = item.key();
    const json& value = item.value();
    if (key == "op" || key == "path") continue;
    if constexpr (std::is_same_v<Options, core::SmoothBrushOptions>) {
      if (key == "passes") {
        const std::string range = "[1, " + std::to_string(core::kMaxSmoothPasses) + "]";
        if (!value.is_number_integer() || value.get<int64_t>() < 1 ||
            value.get<int64_t>() > core::kMaxSmoothPasses)
          return Error(name + ": 'passes' must be a whole number in " + range + ", got " +
                       value.dump());
        o.passes = value.get<int>();
        continue;
      }
    }
    bool known = false;
    for (const auto& [k, member] : keys) {
      if (key != k) continue;
      auto v = number(j, k);
      if (!v) return v.error().in(name);
      o.*member = static_cast<float>(*v);
      known = true;
    }
    if (!known) {
      std::string allowed = "op, path";
      for (const auto& [k, member] : keys)
        allowed += std::string(", ") + k;
      if constexpr (std::is_same_v<Options, core::SmoothBrushOptions>) allowed += ", passes";
      return Error(name + ": unknown key '" + key + "' (" + allowed + ")");
    }
  }
  if (Status st = check(o); !st) return st.error().in(name);
  b.options = o;
  return Op{std::move(b)};
}

Result<Op> parse_op(const json& j, glm::ivec3 dims) {
  if (!j.is_object() || !j.contains("op") || !j["op"].is_string()) {
    return Error("expected an object with a string 'op'");
  }
  const std::string op = j["op"];
  if (op == "tool") {
    if (!j.contains("shape") || !j["shape"].is_string())
      return Error("tool: missing string 'shape'");
    ToolOp t{j["shape"], 0.0, 0.0, {}, {}, 1.0};
    if (Status st = read_hardness(j, t); !st) return st.error();
    if (Status st = read_scale(j, t); !st) return st.error();
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
      for (int a = 0; a < 6; ++a) {
        // Checked before the conversion to int, which is undefined out of range.
        if (v[a] < 0.0 || v[a] > dims[a % 3])
          return Error("tool region: 'box' must be a non-empty box inside the volume");
      }
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
        if (x != std::floor(x)) return Error("tool region: 'box' must be whole voxel indices");
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
    const Result<std::string> value = text(j, "value", "");
    if (!value) return value.error().in("sampling");
    const std::string& v = *value;
    if (v == "nearest") return Op{SamplingOp{core::Sampling::kNearest}};
    if (v == "trilinear") return Op{SamplingOp{core::Sampling::kTrilinear}};
    return Error("sampling: 'value' must be \"nearest\" or \"trilinear\"");
  }
  if (op == "mirror") {
    const Result<std::string> axis_text = text(j, "axis", "");
    if (!axis_text) return axis_text.error().in("mirror");
    const std::string& axis = *axis_text;
    if (axis == "off") return Op{MirrorOp{std::nullopt}};
    if (axis != "x" && axis != "y" && axis != "z")
      return Error("mirror: 'axis' must be x, y, z or off");
    auto c = number(j, "centre");
    if (!c) return c.error().in("mirror");
    if (std::fabs(*c) > sim::kMaxCoordinateVox)
      return Error("mirror: 'centre' is farther than " +
                   std::to_string(int(sim::kMaxCoordinateVox)) + " voxels");
    return Op{MirrorOp{core::MirrorPlane{axis[0] - 'x', static_cast<float>(*c)}}};
  }
  if (op == "begin" || op == "end") return Op{StrokeOp{op == "begin"}};
  if (op == "undo" || op == "redo") return Op{UndoOp{op == "redo"}};
  if (op == "stroke") return parse_stroke(j, dims);
  using core::ClayBrushOptions, core::FlattenBrushOptions, core::GrabBrushOptions,
      core::InflateBrushOptions, core::PinchBrushOptions, core::SmoothBrushOptions;
  if (op == "smooth")
    return parse_brush<SmoothBrushOptions>(j, dims, op,
                                           {{"radius", &SmoothBrushOptions::radius_vox},
                                            {"hardness", &SmoothBrushOptions::hardness},
                                            {"strength", &SmoothBrushOptions::strength}},
                                           core::check_smooth_brush);
  if (op == "clay")
    return parse_brush<ClayBrushOptions>(j, dims, op,
                                         {{"radius", &ClayBrushOptions::radius_vox},
                                          {"hardness", &ClayBrushOptions::hardness},
                                          {"strength", &ClayBrushOptions::strength},
                                          {"layer", &ClayBrushOptions::layer}},
                                         core::check_clay_brush);
  if (op == "flatten")
    return parse_brush<FlattenBrushOptions>(j, dims, op,
                                            {{"radius", &FlattenBrushOptions::radius_vox},
                                             {"hardness", &FlattenBrushOptions::hardness},
                                             {"strength", &FlattenBrushOptions::strength}},
                                            core::check_flatten_brush);
  if (op == "inflate")
    return parse_brush<InflateBrushOptions>(j, dims, op,
                                            {{"radius", &InflateBrushOptions::radius_vox},
                                             {"hardness", &InflateBrushOptions::hardness},
                                             {"strength", &InflateBrushOptions::strength},
                                             {"distance", &InflateBrushOptions::distance_vox}},
                                            core::check_inflate_brush);
  if (op == "pinch")
    return parse_brush<PinchBrushOptions>(j, dims, op,
                                          {{"radius", &PinchBrushOptions::radius_vox},
                                           {"hardness", &PinchBrushOptions::hardness},
                                           {"strength", &PinchBrushOptions::strength}},
                                          core::check_pinch_brush);
  if (op == "grab")
    return parse_brush<GrabBrushOptions>(j, dims, op,
                                         {{"radius", &GrabBrushOptions::radius_vox},
                                          {"hardness", &GrabBrushOptions::hardness},
                                          {"strength", &GrabBrushOptions::strength}},
                                         core::check_grab_brush);
  if (op == "dab") {
    core::Dab d;
    auto at = numbers(j, "at", 3);
    if (!at) return at.error().in("dab");
    if (Status st = check_point(at->data(), dims, "'at'"); !st) return st.error().in("dab");
    d.position_vox = glm::vec3((*at)[0], (*at)[1], (*at)[2]);
    const Result<std::string> mode_text = text(j, "mode", "add");
    if (!mode_text) return mode_text.error().in("dab");
    const std::string& mode = *mode_text;
    const auto m = core::parse_sculpt_mode(mode);
    if (!m)
      return Error("dab: unknown mode '" + mode + "' (add, subtract, union, difference, smooth)");
    d.mode = *m;
    if (j.contains("strength")) {
      auto s = number(j, "strength");
      if (!s || *s < 0.0 || *s > 1.0) return Error("dab: 'strength' must be a number in [0, 1]");
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

}  // namespace

Result<std::vector<Line>> parse(std::istream& in, const std::string& name, glm::ivec3 volume_dims) {
  std::vector<Line> lines;
  std::string text;
  for (int n = 1; std::getline(in, text); ++n) {
    const std::string where = name + ":" + std::to_string(n);
    if (!text.empty() && text.back() == '\r') text.pop_back();
    const size_t first = text.find_first_not_of(" \t");
    if (first == std::string::npos || text[first] == '#') continue;
    const json j = json::parse(text, nullptr, false);
    if (j.is_discarded()) return Error("not valid JSON").in(where);
    auto op = parse_op(j, volume_dims);
    if (!op) return op.error().in(where);
    lines.push_back(Line{n, std::move(op.value())});
  }
  if (in.bad()) return Error("read error").in(name);
  return lines;
}

Result<std::vector<Line>> read(const std::string& path, glm::ivec3 volume_dims) {
  if (const Status s = check_input_file(path); !s) return s.error();
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error("cannot open the dab script").in(path);
  return parse(in, path, volume_dims);
}

}  // namespace sculpt::station::dab_script
