#include "sculpt/hal/normalizer/normalizer_config.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "sculpt/base/input_file.h"

namespace sculpt::hal {
namespace {

constexpr std::array<std::string_view, 6> kAxisNames{"tx", "ty", "tz", "rx", "ry", "rz"};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r'))
    s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> words(std::string_view s) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t'))
      ++i;
    size_t j = i;
    while (j < s.size() && s[j] != ' ' && s[j] != '\t')
      ++j;
    if (j > i) out.push_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

int axis_index(std::string_view name) {
  for (int i = 0; i < 6; ++i) {
    if (kAxisNames[i] == name) return i;
  }
  return -1;
}

bool parse_float(std::string_view s, float& out) {
  const std::string str(s);
  char* end = nullptr;
  const float v = std::strtof(str.c_str(), &end);
  if (str.empty() || end != str.c_str() + str.size() || !std::isfinite(v)) return false;
  out = v;
  return true;
}

std::string fmt(float v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

}  // namespace

Result<NormalizerConfig> parse_normalizer_config(std::string_view text, const std::string& name) {
  NormalizerConfig c;
  int line_no = 0;
  size_t pos = 0;
  while (pos <= text.size()) {
    size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    std::string_view line = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++line_no;
    if (const size_t hash = line.find('#'); hash != std::string_view::npos)
      line = line.substr(0, hash);
    line = trim(line);
    if (line.empty()) {
      if (eol == text.size()) break;
      continue;
    }
    const std::string where = name + ":" + std::to_string(line_no) + ": ";
    const size_t eq = line.find('=');
    if (eq == std::string_view::npos)
      return Error(where + "expected 'key = value', got '" + std::string(line) + "'");
    const std::string_view key = trim(line.substr(0, eq));
    const std::string_view value = trim(line.substr(eq + 1));
    const std::string k(key);
    auto number = [&](float lo, float hi, float& out) -> Status {
      float v = 0;
      if (!parse_float(value, v) || v < lo || v > hi) {
        return Error(where + k + ": expected a number in [" + fmt(lo) + ", " + fmt(hi) +
                     "], got '" + std::string(value) + "'");
      }
      out = v;
      return {};
    };
    // "deadzone", "deadzone.tx", "sensitivity.translation", ...
    const size_t dot = key.find('.');
    const std::string_view base = key.substr(0, dot);
    const std::string_view sub =
        dot == std::string_view::npos ? std::string_view{} : key.substr(dot + 1);
    if (base == "deadzone" || base == "sensitivity") {
      const bool dz = base == "deadzone";
      float v = 0;
      if (auto st = dz ? number(0.0f, 0.9f, v) : number(0.0f, 10.0f, v); !st) return st.error();
      if (!dz && v <= 0.0f) return Error(where + k + ": must be above 0");
      auto& arr = dz ? c.deadzone : c.sensitivity;
      if (sub.empty()) {
        arr.fill(v);
      } else if (sub == "translation") {
        std::fill(arr.begin(), arr.begin() + 3, v);
      } else if (sub == "rotation") {
        std::fill(arr.begin() + 3, arr.end(), v);
      } else if (int a = axis_index(sub); a >= 0) {
        arr[a] = v;
      } else {
        return Error(where + "unknown axis '" + std::string(sub) +
                     "' (want translation, rotation, tx, ty, tz, rx, ry or rz)");
      }
    } else if (key == "curve") {
      const auto w = words(value);
      if (w.size() == 1 && w[0] == "linear") {
        c.curve = CurveKind::kLinear;
        c.curve_param = 0.0f;
      } else if (w.size() == 2 && w[0] == "cubic" && parse_float(w[1], c.curve_param) &&
                 c.curve_param >= 0.0f && c.curve_param <= 1.0f) {
        c.curve = CurveKind::kCubic;
      } else if (w.size() == 2 && w[0] == "power" && parse_float(w[1], c.curve_param) &&
                 c.curve_param >= 1.0f && c.curve_param <= 4.0f) {
        c.curve = CurveKind::kPower;
      } else {
        return Error(where + "curve: expected linear, cubic K (0..1) or power P (1..4), got '" +
                     std::string(value) + "'");
      }
    } else if (key == "map") {
      const auto w = words(value);
      if (w.size() != 6) {
        return Error(where + "map: expected 6 axis names, got " + std::to_string(w.size()));
      }
      std::array<bool, 6> used{};
      for (int i = 0; i < 6; ++i) {
        std::string_view n = w[i];
        int8_t sign = 1;
        if (!n.empty() && n.front() == '-') {
          sign = -1;
          n.remove_prefix(1);
        }
        const int a = axis_index(n);
        if (a < 0) return Error(where + "map: unknown axis '" + std::string(w[i]) + "'");
        if (used[a]) return Error(where + "map: axis '" + std::string(n) + "' used twice");
        used[a] = true;
        c.map_source[i] = static_cast<uint8_t>(a);
        c.map_sign[i] = sign;
      }
    } else if (key == "lock") {
      if (value == "none")
        c.lock = AxisLock::kNone;
      else if (value == "translation")
        c.lock = AxisLock::kTranslation;
      else if (value == "rotation")
        c.lock = AxisLock::kRotation;
      else
        return Error(where + "lock: expected none, translation or rotation, got '" +
                     std::string(value) + "'");
    } else if (key == "dominant" || key == "filter") {
      bool on = false;
      if (value == "on")
        on = true;
      else if (value != "off")
        return Error(where + k + ": expected on or off, got '" + std::string(value) + "'");
      (key == "dominant" ? c.dominant : c.filter) = on;
    } else if (key == "filter.min_cutoff_hz") {
      if (auto st = number(0.01f, 100.0f, c.filter_params.min_cutoff_hz); !st) return st.error();
    } else if (key == "filter.beta") {
      if (auto st = number(0.0f, 100.0f, c.filter_params.beta); !st) return st.error();
    } else if (key == "filter.d_cutoff_hz") {
      if (auto st = number(0.01f, 100.0f, c.filter_params.d_cutoff_hz); !st) return st.error();
    } else {
      return Error(where + "unknown key '" + k + "'");
    }
    if (eol == text.size()) break;
  }
  return c;
}

Result<NormalizerConfig> load_normalizer_config(const std::string& path) {
  if (const Status s = check_input_file(path); !s) return s.error();
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error(path + ": cannot open");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) return Error(path + ": read failed");
  return parse_normalizer_config(ss.str(), path);
}

std::string default_normalizer_config_path() {
  if (const char* p = std::getenv("SCULPT_INPUT_CONFIG"); p && *p) return p;
  if (const char* x = std::getenv("XDG_CONFIG_HOME"); x && *x)
    return std::string(x) + "/sculpt/input.conf";
  if (const char* h = std::getenv("HOME"); h && *h)
    return std::string(h) + "/.config/sculpt/input.conf";
  return "input.conf";
}

Result<NormalizerConfig> load_normalizer_config_or_defaults(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return NormalizerConfig{};
  return load_normalizer_config(path);
}

std::string to_text(const NormalizerConfig& c) {
  std::ostringstream os;
  os.precision(9);  // enough digits for a float to read back equal
  for (int i = 0; i < 6; ++i)
    os << "deadzone." << kAxisNames[i] << " = " << c.deadzone[i] << "\n";
  for (int i = 0; i < 6; ++i)
    os << "sensitivity." << kAxisNames[i] << " = " << c.sensitivity[i] << "\n";
  switch (c.curve) {
    case CurveKind::kLinear:
      os << "curve = linear\n";
      break;
    case CurveKind::kCubic:
      os << "curve = cubic " << c.curve_param << "\n";
      break;
    case CurveKind::kPower:
      os << "curve = power " << c.curve_param << "\n";
      break;
  }
  os << "map =";
  for (int i = 0; i < 6; ++i)
    os << ' ' << (c.map_sign[i] < 0 ? "-" : "") << kAxisNames[c.map_source[i]];
  os << "\nlock = "
     << (c.lock == AxisLock::kNone          ? "none"
         : c.lock == AxisLock::kTranslation ? "translation"
                                            : "rotation")
     << "\ndominant = " << (c.dominant ? "on" : "off") << "\nfilter = " << (c.filter ? "on" : "off")
     << "\nfilter.min_cutoff_hz = " << c.filter_params.min_cutoff_hz
     << "\nfilter.beta = " << c.filter_params.beta
     << "\nfilter.d_cutoff_hz = " << c.filter_params.d_cutoff_hz << "\n";
  return os.str();
}

}  // namespace sculpt::hal
