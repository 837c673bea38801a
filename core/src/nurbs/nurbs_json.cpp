// JSON files of curves, surfaces and zones. Every field is checked before it
// is used, so a bad file is one error line naming the field, never a crash.

#include "sculpt/core/nurbs/nurbs_json.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "sculpt/base/atomic_file.h"

namespace sculpt::core::nurbs {
namespace {

using nlohmann::json;

Result<json> parse(const std::string& text) {
  try {
    json j = json::parse(text);
    if (!j.is_object()) return Error("expected a JSON object");
    return j;
  } catch (const json::parse_error& e) {
    return Error("not valid JSON (at byte " + std::to_string(e.byte) + ")");
  } catch (const json::exception&) {
    // out_of_range 406: a number beyond a double, e.g. 1e400 (found by fuzzing).
    return Error("a number is out of range for a double");
  }
}

Status check_type(const json& j, const char* type) {
  if (!j.contains("type")) return {};
  if (!j["type"].is_string() || j["type"].get<std::string>() != type) {
    return Error(std::string("\"type\" must be \"") + type + "\"");
  }
  return {};
}

Result<int> get_int(const json& j, const char* key) {
  if (!j.contains(key)) return Error(std::string("missing \"") + key + "\"");
  const json& v = j[key];
  if (!v.is_number_integer()) return Error(std::string("\"") + key + "\" must be an integer");
  const auto x = v.get<int64_t>();
  if (x < -1000000000 || x > 1000000000)
    return Error(std::string("\"") + key + "\" is out of range");
  return static_cast<int>(x);
}

Result<double> get_number(const json& j, const char* key) {
  if (!j.contains(key)) return Error(std::string("missing \"") + key + "\"");
  if (!j[key].is_number()) return Error(std::string("\"") + key + "\" must be a number");
  return j[key].get<double>();
}

Result<std::vector<double>> get_numbers(const json& j, const char* key) {
  if (!j.contains(key)) return Error(std::string("missing \"") + key + "\"");
  const json& a = j[key];
  if (!a.is_array()) return Error(std::string("\"") + key + "\" must be an array of numbers");
  std::vector<double> out;
  out.reserve(a.size());
  for (size_t i = 0; i < a.size(); ++i) {
    if (!a[i].is_number()) {
      return Error(std::string(key) + "[" + std::to_string(i) + "] is not a number");
    }
    out.push_back(a[i].get<double>());
  }
  return out;
}

// An array of `dims`-number arrays, flattened.
Result<std::vector<double>> get_tuples(const json& j, const char* key, size_t dims) {
  if (!j.contains(key)) return Error(std::string("missing \"") + key + "\"");
  const json& a = j[key];
  if (!a.is_array()) return Error(std::string("\"") + key + "\" must be an array");
  std::vector<double> out;
  out.reserve(a.size() * dims);
  for (size_t i = 0; i < a.size(); ++i) {
    const json& p = a[i];
    if (!p.is_array() || p.size() != dims) {
      return Error(std::string(key) + "[" + std::to_string(i) + "]: expected " +
                   std::to_string(dims) + " numbers");
    }
    for (size_t k = 0; k < dims; ++k) {
      if (!p[k].is_number()) {
        return Error(std::string(key) + "[" + std::to_string(i) + "]: expected " +
                     std::to_string(dims) + " numbers");
      }
      out.push_back(p[k].get<double>());
    }
  }
  return out;
}

std::vector<glm::dvec3> to_points(const std::vector<double>& flat) {
  std::vector<glm::dvec3> p(flat.size() / 3);
  for (size_t i = 0; i < p.size(); ++i)
    p[i] = {flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]};
  return p;
}

Result<std::string> slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error(path.string() + ": cannot open");
  std::stringstream s;
  s << in.rdbuf();
  if (in.bad()) return Error(path.string() + ": read failed");
  return s.str();
}

std::string num(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

std::string numbers(const std::vector<double>& v) {
  std::string s = "[";
  for (size_t i = 0; i < v.size(); ++i)
    s += (i ? ", " : "") + num(v[i]);
  return s + "]";
}

std::string points(const std::vector<glm::dvec3>& p) {
  std::string s = "[\n";
  for (size_t i = 0; i < p.size(); ++i) {
    s += "    [" + num(p[i].x) + ", " + num(p[i].y) + ", " + num(p[i].z) + "]";
    s += i + 1 < p.size() ? ",\n" : "\n";
  }
  return s + "  ]";
}

Status write_text(const std::filesystem::path& path, const std::string& text) {
  AtomicFileWriter out(path);
  if (!out.ok()) return out.error();
  out.write(text);
  return out.commit();
}

template <class T, class Parse>
Result<T> read_with(const std::filesystem::path& path, Parse parse_fn) {
  Result<std::string> text = slurp(path);
  if (!text) return text.error();
  Result<T> r = parse_fn(*text);
  if (!r) return r.error().in(path.string());
  return r;
}

}  // namespace

Result<NurbsSurface> parse_surface_json(const std::string& text) {
  Result<json> parsed = parse(text);
  if (!parsed) return parsed.error();
  const json& j = *parsed;
  if (Status st = check_type(j, "nurbs_surface"); !st) return st.error();
  NurbsSurface s;
  Result<int> du = get_int(j, "degree_u"), dv = get_int(j, "degree_v");
  Result<int> cu = get_int(j, "count_u"), cv = get_int(j, "count_v");
  for (const Result<int>* r : {&du, &dv, &cu, &cv}) {
    if (!*r) return r->error();
  }
  s.degree_u = *du;
  s.degree_v = *dv;
  s.count_u = *cu;
  s.count_v = *cv;
  if (s.count_u < 1 || s.count_v < 1) return Error("count_u and count_v must be positive");
  if (static_cast<int64_t>(s.count_u) * s.count_v > 100'000'000) {
    return Error("count_u x count_v is too large");
  }
  Result<std::vector<double>> ku = get_numbers(j, "knots_u");
  if (!ku) return ku.error();
  Result<std::vector<double>> kv = get_numbers(j, "knots_v");
  if (!kv) return kv.error();
  Result<std::vector<double>> cp = get_tuples(j, "control_points", 3);
  if (!cp) return cp.error();
  s.knots_u = std::move(*ku);
  s.knots_v = std::move(*kv);
  s.points = to_points(*cp);
  if (j.contains("weights")) {
    Result<std::vector<double>> w = get_numbers(j, "weights");
    if (!w) return w.error();
    s.weights = std::move(*w);
  }
  if (Status st = validate(s); !st) return st.error();
  return s;
}

Result<NurbsCurve> parse_curve_json(const std::string& text) {
  Result<json> parsed = parse(text);
  if (!parsed) return parsed.error();
  const json& j = *parsed;
  if (Status st = check_type(j, "nurbs_curve"); !st) return st.error();
  NurbsCurve c;
  Result<int> d = get_int(j, "degree");
  if (!d) return d.error();
  c.degree = *d;
  Result<std::vector<double>> k = get_numbers(j, "knots");
  if (!k) return k.error();
  Result<std::vector<double>> cp = get_tuples(j, "control_points", 3);
  if (!cp) return cp.error();
  c.knots = std::move(*k);
  c.points = to_points(*cp);
  if (j.contains("weights")) {
    Result<std::vector<double>> w = get_numbers(j, "weights");
    if (!w) return w.error();
    c.weights = std::move(*w);
  }
  if (Status st = validate(c); !st) return st.error();
  return c;
}

Result<ParameterZone> parse_zone_json(const std::string& text) {
  Result<json> parsed = parse(text);
  if (!parsed) return parsed.error();
  const json& j = *parsed;
  if (Status st = check_type(j, "zone"); !st) return st.error();
  if (!j.contains("shape") || !j["shape"].is_string()) {
    return Error("missing \"shape\" (\"circle\" or \"polygon\")");
  }
  const std::string shape = j["shape"].get<std::string>();
  ParameterZone z;
  if (shape == "circle") {
    z.shape = ParameterZone::Shape::kCircle;
    const char* key = j.contains("center") ? "center" : "centre";
    Result<std::vector<double>> c = get_numbers(j, key);
    if (!c) return c.error();
    if (c->size() != 2) return Error(std::string("\"") + key + "\" must hold 2 numbers (u, v)");
    z.centre = {(*c)[0], (*c)[1]};
    Result<double> r = get_number(j, "radius");
    if (!r) return r.error();
    z.radius = *r;
    if (!(z.radius > 0.0) || !std::isfinite(z.radius)) return Error("\"radius\" must be positive");
  } else if (shape == "polygon") {
    z.shape = ParameterZone::Shape::kPolygon;
    Result<std::vector<double>> p = get_tuples(j, "points", 2);
    if (!p) return p.error();
    for (size_t i = 0; i + 1 < p->size(); i += 2)
      z.polygon.emplace_back((*p)[i], (*p)[i + 1]);
    if (z.polygon.size() < 3) return Error("polygon: needs at least 3 points");
  } else {
    return Error("\"shape\" must be \"circle\" or \"polygon\", got \"" + shape + "\"");
  }
  return z;
}

Result<NurbsSurface> read_surface_json(const std::filesystem::path& path) {
  return read_with<NurbsSurface>(path, parse_surface_json);
}
Result<NurbsCurve> read_curve_json(const std::filesystem::path& path) {
  return read_with<NurbsCurve>(path, parse_curve_json);
}
Result<ParameterZone> read_zone_json(const std::filesystem::path& path) {
  return read_with<ParameterZone>(path, parse_zone_json);
}

std::string to_json(const NurbsSurface& s) {
  std::string t = "{\n  \"type\": \"nurbs_surface\",\n";
  t += "  \"degree_u\": " + std::to_string(s.degree_u) + ",\n";
  t += "  \"degree_v\": " + std::to_string(s.degree_v) + ",\n";
  t += "  \"count_u\": " + std::to_string(s.count_u) + ",\n";
  t += "  \"count_v\": " + std::to_string(s.count_v) + ",\n";
  t += "  \"knots_u\": " + numbers(s.knots_u) + ",\n";
  t += "  \"knots_v\": " + numbers(s.knots_v) + ",\n";
  t += "  \"control_points\": " + points(s.points);
  if (s.rational()) t += ",\n  \"weights\": " + numbers(s.weights);
  return t + "\n}\n";
}

std::string to_json(const NurbsCurve& c) {
  std::string t = "{\n  \"type\": \"nurbs_curve\",\n";
  t += "  \"degree\": " + std::to_string(c.degree) + ",\n";
  t += "  \"knots\": " + numbers(c.knots) + ",\n";
  t += "  \"control_points\": " + points(c.points);
  if (c.rational()) t += ",\n  \"weights\": " + numbers(c.weights);
  return t + "\n}\n";
}

std::string to_json(const ParameterZone& z) {
  if (z.shape == ParameterZone::Shape::kCircle) {
    return "{\n  \"type\": \"zone\",\n  \"shape\": \"circle\",\n  \"centre\": [" + num(z.centre.x) +
           ", " + num(z.centre.y) + "],\n  \"radius\": " + num(z.radius) + "\n}\n";
  }
  std::string t = "{\n  \"type\": \"zone\",\n  \"shape\": \"polygon\",\n  \"points\": [";
  for (size_t i = 0; i < z.polygon.size(); ++i) {
    t += (i ? ", [" : "[") + num(z.polygon[i].x) + ", " + num(z.polygon[i].y) + "]";
  }
  return t + "]\n}\n";
}

// Only what the readers accept is written: a result that left the limits
// (nurbs_limits.h) or went non-finite is refused, never saved as NaN.
Status write_json(const std::filesystem::path& path, const NurbsSurface& s) {
  if (Status st = validate(s); !st) return st.error().in(path.string() + ": not written");
  return write_text(path, to_json(s));
}
Status write_json(const std::filesystem::path& path, const NurbsCurve& c) {
  if (Status st = validate(c); !st) return st.error().in(path.string() + ": not written");
  return write_text(path, to_json(c));
}
Status write_json(const std::filesystem::path& path, const ParameterZone& z) {
  return write_text(path, to_json(z));
}

}  // namespace sculpt::core::nurbs
