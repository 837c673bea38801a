#include "sculpt/hal/force/hand_script.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "sculpt/base/input_file.h"

namespace sculpt::hal {
namespace {

constexpr double kMaxTimeS = 24.0 * 3600.0;
constexpr double kMaxPositionMm = 1000.0;

// The words of a line before any '#'.
std::vector<std::string_view> words_of(std::string_view line) {
  line = line.substr(0, line.find('#'));
  std::vector<std::string_view> words;
  size_t at = 0;
  while (at < line.size()) {
    while (at < line.size() && (line[at] == ' ' || line[at] == '\t' || line[at] == '\r'))
      ++at;
    size_t end = at;
    while (end < line.size() && line[end] != ' ' && line[end] != '\t' && line[end] != '\r')
      ++end;
    if (end > at) words.push_back(line.substr(at, end - at));
    at = end;
  }
  return words;
}

// Built by append: GCC 12 warns (-Wrestrict, a false positive) on "'" + std::string(word).
std::string quoted(std::string_view word) {
  std::string q(1, '\'');
  q.append(word);
  q.push_back('\'');
  return q;
}

bool to_double(std::string_view word, double& out) {
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), out);
  return error == std::errc() && end == word.data() + word.size() && std::isfinite(out);
}

}  // namespace

glm::vec3 HandScript::target_at(double t_s) const {
  if (path.empty()) return glm::vec3(0.0f);
  const auto after = std::upper_bound(path.begin(), path.end(), t_s,
                                      [](double t, const HandWaypoint& w) { return t < w.t_s; });
  if (after == path.begin()) return path.front().target_mm;
  if (after == path.end()) return path.back().target_mm;
  const HandWaypoint& a = *(after - 1);
  const HandWaypoint& b = *after;
  const double span = b.t_s - a.t_s;
  const float f = span > 0.0 ? static_cast<float>((t_s - a.t_s) / span) : 1.0f;
  return a.target_mm + (b.target_mm - a.target_mm) * f;
}

uint32_t HandScript::buttons_at(double t_s) const {
  uint32_t mask = 0;
  for (const HandButtons& b : buttons) {
    if (b.t_s > t_s) break;
    mask = b.mask;
  }
  return mask;
}

double HandScript::end_s() const {
  double end = path.empty() ? 0.0 : path.back().t_s;
  if (!buttons.empty()) end = std::max(end, buttons.back().t_s);
  return std::max(end, unplug_s);
}

Result<HandScript> parse_hand_script(std::string_view text, const std::string& source) {
  HandScript script;
  int line_number = 0;
  bool have_header = false;
  size_t at = 0;
  while (at <= text.size()) {
    const size_t end = std::min(text.find('\n', at), text.size());
    const std::vector<std::string_view> words = words_of(text.substr(at, end - at));
    at = end + 1;
    ++line_number;
    if (words.empty()) continue;
    const auto fail = [&](const std::string& what) {
      return Error(source + ":" + std::to_string(line_number) + ": " + what);
    };
    std::vector<double> numbers;
    for (size_t i = 1; i < words.size(); ++i) {
      double v = 0.0;
      if (!to_double(words[i], v)) return fail(quoted(words[i]) + " is not a finite number");
      numbers.push_back(v);
    }
    const std::string_view keyword = words[0];
    const auto want = [&](size_t n) { return numbers.size() == n; };
    if (!have_header) {
      if (keyword != "sculpt-hand" || !want(1) || numbers[0] != 1.0)
        return fail("expected the header 'sculpt-hand 1'");
      have_header = true;
      continue;
    }
    const auto check_time = [&](double t) { return t >= 0.0 && t <= kMaxTimeS; };
    if (keyword == "grip") {
      if (!want(2) || numbers[0] < 0.0 || numbers[0] > 100.0 || numbers[1] < 0.0 ||
          numbers[1] > 1000.0)
        return fail("grip takes a stiffness in [0, 100] N/mm and a damping in [0, 1000] N·s/m");
      script.stiffness_n_per_mm = static_cast<float>(numbers[0]);
      script.damping_ns_per_m = static_cast<float>(numbers[1]);
    } else if (keyword == "at") {
      if (!want(4)) return fail("at takes a time (s) and x y z (mm)");
      if (!check_time(numbers[0])) return fail("time out of [0, 86400] s");
      if (!script.path.empty() && numbers[0] < script.path.back().t_s)
        return fail("time goes backwards");
      for (int i = 1; i <= 3; ++i)
        if (std::abs(numbers[i]) > kMaxPositionMm) return fail("position beyond 1000 mm");
      script.path.push_back({numbers[0], glm::vec3(numbers[1], numbers[2], numbers[3])});
    } else if (keyword == "buttons") {
      if (!want(2) || numbers[1] < 0.0 || numbers[1] > 4294967295.0 ||
          numbers[1] != std::floor(numbers[1]))
        return fail("buttons takes a time (s) and a mask (an integer of 32 bits)");
      if (!check_time(numbers[0])) return fail("time out of [0, 86400] s");
      if (!script.buttons.empty() && numbers[0] < script.buttons.back().t_s)
        return fail("time goes backwards");
      script.buttons.push_back({numbers[0], static_cast<uint32_t>(numbers[1])});
    } else if (keyword == "unplug") {
      if (!want(1) || !check_time(numbers[0])) return fail("unplug takes a time in [0, 86400] s");
      script.unplug_s = numbers[0];
    } else {
      return fail("unknown statement " + quoted(keyword) + " (grip, at, buttons, unplug)");
    }
  }
  if (!have_header) return Error(source + ": empty; expected the header 'sculpt-hand 1'");
  if (script.path.empty()) return Error(source + ": no 'at' line: the hand goes nowhere");
  return script;
}

Result<HandScript> read_hand_script(const std::string& path) {
  constexpr std::streamoff kMaxBytes = 64 << 20;
  if (const Status s = check_input_file(path); !s) return s.error();
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return Error(path + ": cannot open");
  if (in.tellg() > kMaxBytes) return Error(path + ": larger than 64 MB: not a hand script");
  in.seekg(0);
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return Error(path + ": cannot read");
  return parse_hand_script(text.str(), path);
}

}  // namespace sculpt::hal
