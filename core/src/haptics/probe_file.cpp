// Probe files and trace lines. Every line is bounded (length, count) before
// the JSON parser sees it, and every value is range-checked before it is
// converted, so any bytes give either the samples or one error line: never an
// exception out of here, never undefined behaviour.

#include "sculpt/core/haptics/probe_file.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <memory>

#include <nlohmann/json.hpp>

namespace sculpt::core {
namespace {

using nlohmann::json;

constexpr double kQuatLengthTolerance = 1e-3;

// Shortest text that reads back as `v`, for messages.
std::string number_text(double v) {
  char buf[32];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

// A key as it can appear in a one-line message: quoted, escaped, not too long.
std::string shown_key(const std::string& key) {
  constexpr size_t kMaxShown = 40;
  std::string s =
      json(key.substr(0, kMaxShown)).dump(-1, ' ', false, json::error_handler_t::replace);
  return key.size() > kMaxShown ? s + "..." : s;
}

// The letters around line[i], lower case.
std::string word_at(std::string_view line, size_t i) {
  const auto letter = [&](size_t k) {
    return k < line.size() && std::isalpha(static_cast<unsigned char>(line[k]));
  };
  size_t begin = i, end = i;
  while (begin > 0 && letter(begin - 1))
    --begin;
  while (letter(end))
    ++end;
  std::string word;
  for (size_t k = begin; k < end; ++k)
    word += static_cast<char>(std::tolower(static_cast<unsigned char>(line[k])));
  return word;
}

// The throwing parse, caught, because its exception says where and why. NaN
// and Infinity get their own hint: other tools (Python's json.dumps) write
// them, and JSON has no such numbers.
Result<json> parse_object(std::string_view line) {
  try {
    json j = json::parse(line);
    if (!j.is_object()) return Error("not a JSON object");
    return j;
  } catch (const json::parse_error& e) {
    const size_t column = std::min<size_t>(e.byte, line.size());
    std::string problem = "not a JSON object (invalid JSON at column " + std::to_string(column);
    // The parser stops inside the word ("nan" fails at its 'a', expecting "null").
    const std::string word = word_at(line, column > 0 ? column - 1 : 0);
    if (word == "nan" || word == "inf" || word == "infinity")
      problem += ": NaN and Infinity are not JSON numbers";
    return Error(problem + ")");
  } catch (const json::exception&) {
    // out_of_range 406: a number beyond a double, e.g. 1e400.
    return Error("a number is out of range for a double");
  }
}

// The checks every line of both formats shares; then read(object), whose
// error gets the "NAME:LINE: " prefix.
template <class Read>
Status for_each_object(std::string_view text, const std::string& name,
                       std::initializer_list<std::string_view> keys, Read read) {
  size_t line_no = 0;
  while (!text.empty()) {
    const size_t nl = text.find('\n');
    const std::string_view line = text.substr(0, nl);
    text = nl == std::string_view::npos ? std::string_view() : text.substr(nl + 1);
    ++line_no;
    const auto error = [&](const std::string& problem) {
      return Error(name + ":" + std::to_string(line_no) + ": " + problem);
    };
    if (line_no > kMaxProbeLines)
      return error("too many lines (at most " + std::to_string(kMaxProbeLines) + ")");
    if (line.size() > kMaxProbeLineBytes)
      return error("line too long (more than " + std::to_string(kMaxProbeLineBytes) + " bytes)");
    if (line.find_first_not_of(" \t\r\f\v") == std::string_view::npos) continue;
    const Result<json> j = parse_object(line);
    if (!j) return error(j.error().message());
    for (const auto& item : j->items()) {
      if (std::find(keys.begin(), keys.end(), item.key()) == keys.end())
        return error("unknown key " + shown_key(item.key()));
    }
    if (const Status s = read(*j); !s) return error(s.error().message());
  }
  return {};
}

std::string quoted(const char* key) {
  return std::string("\"") + key + "\"";
}

Result<double> get_time(const json& j) {
  const auto it = j.find("t");
  if (it == j.end()) return Error("missing \"t\"");
  if (!it->is_number() || !std::isfinite(it->get<double>()))
    return Error("\"t\" is not a finite number");
  return it->get<double>();
}

// `n` finite numbers, each at most `max_abs` (so the caller's conversion is defined).
bool get_numbers(const json& a, double* out, size_t n, double max_abs) {
  if (!a.is_array() || a.size() != n) return false;
  for (size_t i = 0; i < n; ++i) {
    if (!a[i].is_number()) return false;
    out[i] = a[i].get<double>();
    if (!std::isfinite(out[i]) || std::abs(out[i]) > max_abs) return false;
  }
  return true;
}

// A required array of 3 numbers that round to finite floats. The bound is
// not FLT_MAX: 9 digits of FLT_MAX ("3.40282347e+38") read as a double just
// above it, and everything below FLT_MAX + half its ulp rounds down to it
// (the midpoint itself rounds to infinity).
Result<glm::vec3> get_vec3(const json& j, const char* key) {
  constexpr double kRoundsToFiniteFloat = 0x1.ffffffp+127;
  const auto it = j.find(key);
  if (it == j.end()) return Error("missing " + quoted(key));
  double v[3];
  if (!get_numbers(*it, v, 3, std::nextafter(kRoundsToFiniteFloat, 0.0)))
    return Error(quoted(key) + " must be 3 finite numbers");
  return glm::vec3(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
}

Status read_probe_sample(const json& j, std::vector<ProbeSample>& samples) {
  ProbeSample p;
  const Result<double> t = get_time(j);
  if (!t) return t.error();
  p.t_s = *t;
  if (samples.empty() && p.t_s < 0.0)
    return Error("the first \"t\" must be >= 0 (got " + number_text(p.t_s) + ")");
  if (!samples.empty() && !(p.t_s > samples.back().t_s)) {
    return Error("\"t\" must increase strictly (" + number_text(p.t_s) + " after " +
                 number_text(samples.back().t_s) + ")");
  }

  const auto at = j.find("at");
  if (at == j.end()) return Error("missing \"at\"");
  double v[3];
  if (!get_numbers(*at, v, 3, std::numeric_limits<double>::max()))
    return Error("\"at\" must be 3 finite numbers");
  for (double c : v) {
    if (std::abs(c) > kMaxProbeCoordinateVox)
      return Error("\"at\" is out of range (" + number_text(c) +
                   ", at most 1e6 voxels either way)");
  }
  p.at_vox =
      glm::vec3(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));

  if (const auto quat = j.find("quat"); quat != j.end()) {
    double q[4];
    // Elements up to 1e300 square to infinity, which fails the length test as it should.
    const bool numbers = get_numbers(*quat, q, 4, std::numeric_limits<double>::max());
    const double length =
        numbers ? std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]) : 0.0;
    if (!(std::abs(length - 1.0) <= kQuatLengthTolerance))
      return Error("\"quat\" must be 4 finite numbers of length 1 (within 1e-3)");
    // Normalised: a quaternion of length 1.0005 would also scale what it rotates.
    p.orientation = glm::quat(static_cast<float>(q[0] / length), static_cast<float>(q[1] / length),
                              static_cast<float>(q[2] / length), static_cast<float>(q[3] / length));
  }
  samples.push_back(p);
  return {};
}

Status read_trace_line(const json& j, std::vector<TraceLine>& lines) {
  TraceLine l;
  const Result<double> t = get_time(j);
  if (!t) return t.error();
  l.t_s = *t;
  const Result<glm::vec3> device = get_vec3(j, "device");
  if (!device) return device.error();
  const Result<glm::vec3> proxy = get_vec3(j, "proxy");
  if (!proxy) return proxy.error();
  const Result<glm::vec3> force = get_vec3(j, "force");
  if (!force) return force.error();
  l.device_vox = *device;
  l.proxy_vox = *proxy;
  l.force_n = *force;
  if (j.contains("torque")) {
    const Result<glm::vec3> torque = get_vec3(j, "torque");
    if (!torque) return torque.error();
    l.torque_nm = *torque;
  }
  const auto contact = j.find("contact");
  if (contact == j.end()) return Error("missing \"contact\"");
  if (!contact->is_boolean()) return Error("\"contact\" must be true or false");
  l.contact = contact->get<bool>();
  lines.push_back(l);
  return {};
}

// %.{digits}g without the locale's decimal comma.
void append_number(std::string& out, double v, int digits) {
  if (!std::isfinite(v)) {
    out += "null";
    return;
  }
  // JSON readers take "-0" for the integer 0; "-0.0" keeps the sign bit.
  if (v == 0.0 && std::signbit(v)) {
    out += "-0.0";
    return;
  }
  char buf[32];
  out.append(buf, std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, digits).ptr);
}

// float: 9 significant digits are enough to read back the same float.
void append_vec3(std::string& out, const char* key, glm::vec3 v) {
  out += ",\"";
  out += key;
  out += "\":[";
  for (int i = 0; i < 3; ++i) {
    if (i > 0) out += ',';
    append_number(out, v[i], 9);
  }
  out += ']';
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

}  // namespace

Result<std::vector<ProbeSample>> parse_probe_text(std::string_view text, const std::string& name) {
  std::vector<ProbeSample> samples;
  const Status s = for_each_object(text, name, {"t", "at", "quat"},
                                   [&](const json& j) { return read_probe_sample(j, samples); });
  if (!s) return s.error();
  if (samples.empty()) return Error(name + ": no probe samples");
  return samples;
}

Result<std::vector<ProbeSample>> read_probe_file(const std::filesystem::path& path) {
  const std::string name = path.string();
  const std::unique_ptr<std::FILE, FileCloser> file(std::fopen(name.c_str(), "rb"));
  if (!file) return Error(name + ": cannot open: " + std::strerror(errno));
  std::string text;
  char buf[65536];
  for (size_t n; (n = std::fread(buf, 1, sizeof buf, file.get())) > 0;)
    text.append(buf, n);
  // A directory opens fine on Linux and fails only here (EISDIR).
  if (std::ferror(file.get())) return Error(name + ": cannot read: " + std::strerror(errno));
  return parse_probe_text(text, name);
}

std::string format_trace_line(const TraceLine& line) {
  std::string out = "{\"t\":";
  append_number(out, line.t_s, 17);
  append_vec3(out, "device", line.device_vox);
  append_vec3(out, "proxy", line.proxy_vox);
  append_vec3(out, "force", line.force_n);
  if (line.torque_nm) append_vec3(out, "torque", *line.torque_nm);
  out += line.contact ? ",\"contact\":true}\n" : ",\"contact\":false}\n";
  return out;
}

bool trace_line_finite(const TraceLine& line) {
  auto finite = [](glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
  };
  return std::isfinite(line.t_s) && finite(line.device_vox) && finite(line.proxy_vox) &&
         finite(line.force_n) && (!line.torque_nm || finite(*line.torque_nm));
}

Result<std::vector<TraceLine>> parse_trace_text(std::string_view text, const std::string& name) {
  std::vector<TraceLine> lines;
  const Status s =
      for_each_object(text, name, {"t", "device", "proxy", "force", "torque", "contact"},
                      [&](const json& j) { return read_trace_line(j, lines); });
  if (!s) return s.error();
  if (lines.empty()) return Error(name + ": no trace lines");
  return lines;
}

}  // namespace sculpt::core
