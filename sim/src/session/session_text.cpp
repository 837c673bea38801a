#include "sculpt/sim/session/session_text.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "sculpt/sim/session/command_limits.h"
#include "sculpt/sim/session/session_file.h"

namespace sculpt::sim {
namespace {

using nlohmann::json;
// Written with keys in a fixed, readable order ("t" first).
using ordered = nlohmann::ordered_json;

std::string to_hex(std::span<const uint8_t> bytes) {
  std::string s;
  char b[4];
  for (size_t i = 0; i < bytes.size(); ++i) {
    std::snprintf(b, sizeof b, i ? " %02x" : "%02x", bytes[i]);
    s += b;
  }
  return s;
}

// Hex digits with optional spaces, tabs, colons or commas between bytes.
std::optional<std::vector<uint8_t>> from_hex(std::string_view s) {
  std::vector<uint8_t> out;
  int pending = -1;
  for (char c : s) {
    int v;
    if (c >= '0' && c <= '9')
      v = c - '0';
    else if (c >= 'a' && c <= 'f')
      v = c - 'a' + 10;
    else if (c >= 'A' && c <= 'F')
      v = c - 'A' + 10;
    else if (c == ' ' || c == '\t' || c == ':' || c == ',') {
      if (pending >= 0) return std::nullopt;  // a lone digit
      continue;
    } else {
      return std::nullopt;
    }
    if (pending < 0) {
      pending = v;
    } else {
      out.push_back(static_cast<uint8_t>(pending * 16 + v));
      pending = -1;
    }
  }
  if (pending >= 0) return std::nullopt;
  return out;
}

// Whether `s` is well-formed UTF-8 (no overlong forms, surrogates or code
// points past U+10FFFF): what a JSON string can carry.
bool is_utf8(std::string_view s) {
  size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    int extra;
    uint32_t cp;
    if (c < 0x80) {
      ++i;
      continue;
    } else if ((c & 0xE0) == 0xC0) {
      extra = 1, cp = c & 0x1F;
    } else if ((c & 0xF0) == 0xE0) {
      extra = 2, cp = c & 0x0F;
    } else if ((c & 0xF8) == 0xF0) {
      extra = 3, cp = c & 0x07;
    } else {
      return false;
    }
    if (i + size_t(extra) >= s.size()) return false;  // cut short
    for (int k = 1; k <= extra; ++k) {
      const auto d = static_cast<unsigned char>(s[i + size_t(k)]);
      if ((d & 0xC0) != 0x80) return false;
      cp = (cp << 6) | (d & 0x3F);
    }
    static constexpr uint32_t kSmallest[] = {0, 0x80, 0x800, 0x10000};
    if (cp < kSmallest[extra] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return false;
    i += size_t(extra) + 1;
  }
  return true;
}

// A device string as JSON: itself when it is UTF-8, else {"bytes": hex}, so
// that a name a device reports in another encoding survives the round trip.
ordered text_field(const std::string& s) {
  if (is_utf8(s)) return s;
  const auto* bytes = reinterpret_cast<const uint8_t*>(s.data());
  return ordered{{"bytes", to_hex({bytes, s.size()})}};
}

// An integer field in [lo, hi]; missing is 0. A float or an out-of-range
// value is refused before any conversion (found by fuzzing: 1.8e124 was
// converted to a uint16_t, undefined behaviour).
int64_t read_integer(const json& object, const char* key, int64_t lo, int64_t hi) {
  if (!object.contains(key)) return 0;
  const json& v = object[key];
  const bool in_range = v.is_number_unsigned()  ? v.get<uint64_t>() <= uint64_t(hi)
                        : v.is_number_integer() ? v.get<int64_t>() >= lo && v.get<int64_t>() <= hi
                                                : false;
  if (!in_range)
    throw std::string(key) + ": expected an integer from " + std::to_string(lo) + " to " +
        std::to_string(hi);
  return v.get<int64_t>();
}

// text_field()'s inverse; missing is empty. Throws like the other readers.
// A header's text field, refused when longer than a session file holds.
std::string read_text_field(const json& object, const char* key, uint32_t max_bytes) {
  if (!object.contains(key)) return {};
  const json& v = object[key];
  std::string text;
  if (v.is_string()) {
    text = v.get<std::string>();
  } else if (v.is_object() && v.contains("bytes") && v["bytes"].is_string()) {
    const auto bytes = from_hex(v["bytes"].get<std::string>());
    if (!bytes) throw std::string(key) + ".bytes: not hex";
    text.assign(bytes->begin(), bytes->end());
  } else {
    throw std::string(key) + ": expected a string or {\"bytes\": hex}";
  }
  if (text.size() > max_bytes) {
    std::string why = key;
    why += ": " + std::to_string(text.size()) + " bytes, more than the ";
    why += std::to_string(max_bytes) + " a session holds";
    throw why;
  }
  return text;
}

ordered floats(const float* v, int n) {
  ordered a = ordered::array();
  for (int i = 0; i < n; ++i)
    a.push_back(v[i]);
  return a;
}

constexpr std::array<const char*, 3> kInfluenceNames = {"natural", "gaussian", "zone"};

void sheet_json(const Command& c, ordered& j) {
  const auto action = static_cast<SheetAction>(c.choice);
  j["action"] = sheet_action_name(action);
  switch (action) {
    case SheetAction::kPlace:
      j["centre"] = floats(c.values, 3);
      j["size"] = c.values[3];
      j["points"] = c.values[4];
      j["axis"] =
          std::string(1, static_cast<char>('x' + std::clamp(static_cast<int>(c.values[5]), 0, 2)));
      break;
    case SheetAction::kEdit: {
      j["on"] = c.values[0] != 0.0f;
      const auto i = static_cast<size_t>(std::clamp(static_cast<int>(c.values[1]), 0, 2));
      j["influence"] = kInfluenceNames[i];
      j["radius"] = c.values[2];
      break;
    }
    case SheetAction::kAdd:
    case SheetAction::kSubtract:
    case SheetAction::kTool:
      j["thickness"] = c.values[0];
      break;
    case SheetAction::kRemove:
      break;
  }
}

void haptic_json(const HapticRecord& h, ordered& j) {
  j["haptic"] = haptic_record_name(h.type);
  switch (h.type) {
    case HapticRecord::Type::kStart:
      j["settings"] = h.settings;
      break;
    case HapticRecord::Type::kPatch:
      j["version"] = h.tag;
      j["centre"] = floats(h.values, 3);
      break;
    case HapticRecord::Type::kTick:
      j["tick_t"] = h.tick_t_ns;
      j["index"] = h.index;
      j["buttons"] = h.buttons;
      j["flags"] = h.flags;
      j["inputs"] = h.tag;
      j["position_mm"] = floats(h.values, 3);
      j["force_n"] = floats(h.values + 3, 3);
      break;
  }
}

ordered record_json(const SessionRecord& r) {
  ordered j;
  j["t"] = r.t_ns();
  if (r.kind == SessionRecord::Kind::kEvent) {
    const hal::RawEvent& e = r.event;
    switch (e.kind) {
      case hal::RawEventKind::kReport:
        j["report"] = to_hex(e.bytes());
        if (e.truncated) j["truncated"] = true;
        break;
      case hal::RawEventKind::kAxis:
        j["axis"] = {e.index, e.value};
        break;
      case hal::RawEventKind::kButton:
        j["button"] = {e.index, e.value};
        break;
      case hal::RawEventKind::kSync:
        j["sync"] = true;
        break;
      case hal::RawEventKind::kRemoved:
        j["removed"] = true;
        break;
    }
    return j;
  }
  if (r.kind == SessionRecord::Kind::kHaptic) {
    haptic_json(r.haptic, j);
    return j;
  }
  const Command& c = r.command;
  j["cmd"] = command_name(c.kind);
  switch (c.kind) {
    case CommandKind::kTool:
      j["shape"] = tool_shape_name(static_cast<ToolShape>(c.choice));
      j["size"] = floats(c.values, 2);
      break;
    case CommandKind::kMode:
      j["mode"] = sculpt_mode_name(static_cast<SculptModeId>(c.choice));
      break;
    case CommandKind::kStrength:
    case CommandKind::kSpacing:
    case CommandKind::kHardness:
    case CommandKind::kToolScale:
      j["value"] = c.values[0];
      break;
    case CommandKind::kMirror:
      j["axis"] =
          c.choice == kMirrorOff ? "off" : std::string(1, static_cast<char>('x' + c.choice));
      j["at"] = c.values[0];
      break;
    case CommandKind::kVolume:
      j["size"] = floats(c.values, 3);
      j[c.choice == kVolumeClay ? "clay_margin" : "fill"] = c.values[3];
      break;
    case CommandKind::kToolPose:
    case CommandKind::kPointer:
      j["position"] = floats(c.values, 3);
      j["orientation"] = floats(c.values + 3, 4);
      break;
    case CommandKind::kToolFromRegion:
      j["lo"] = floats(c.values, 3);
      j["hi"] = floats(c.values + 3, 3);
      break;
    case CommandKind::kHypertexture:
      j["centre"] = floats(c.values, 3);
      j["radius"] = c.values[3];
      j["width"] = c.values[4];
      j["seed"] = c.values[5];
      break;
    case CommandKind::kSheet:
      sheet_json(c, j);
      break;
    case CommandKind::kTouch:
    case CommandKind::kAccumulate:
      j["on"] = c.choice != 0;
      break;
    case CommandKind::kClutch:
      j["held"] = c.choice != 0;
      break;
    case CommandKind::kTracker:
      j["scale_vox_per_mm"] = c.values[0];
      j["rotation"] = floats(c.values + 1, 4);
      break;
    case CommandKind::kMorphology:
      j["op"] = c.choice == kMorphologyClose ? "close" : "offset";
      j["by"] = c.values[0];
      break;
    case CommandKind::kToolVoxels:
      if (c.voxels != nullptr) {
        const ToolVoxels& t = *c.voxels;
        j["dims"] = {t.dims[0], t.dims[1], t.dims[2]};
        j["pivot"] = floats(t.pivot, 3);
        j["hardness"] = t.hardness;
        j["density"] = to_hex(t.density);
      }
      break;
    default:
      break;
  }
  return j;
}

// Field readers: each throws a std::string naming the field and the problem.
const json& need(const json& j, const char* key) {
  if (!j.contains(key)) throw std::string("missing \"") + key + "\"";
  return j.at(key);
}

void read_numbers(const json& j, const char* key, float* out, int n) {
  const json& a = need(j, key);
  if (!a.is_array() || static_cast<int>(a.size()) != n) {
    throw std::string(key) + ": expected " + std::to_string(n) + " numbers";
  }
  for (int i = 0; i < n; ++i) {
    if (!a[static_cast<size_t>(i)].is_number()) throw std::string(key) + ": expected numbers";
    out[i] = a[static_cast<size_t>(i)].get<float>();
  }
}

void read_number(const json& j, const char* key, float* out) {
  const json& v = need(j, key);
  if (!v.is_number()) throw std::string(key) + ": expected a number";
  *out = v.get<float>();
}

// The fields of a sheet command (sheet_json's inverse); throws like the others.
void read_sheet(const json& j, Command& c) {
  const json& a = need(j, "action");
  const auto action = a.is_string() ? parse_sheet_action(a.get<std::string>()) : std::nullopt;
  if (!action) throw std::string("action: unknown value ") + a.dump();
  c.choice = static_cast<uint8_t>(*action);
  switch (*action) {
    case SheetAction::kPlace: {
      read_numbers(j, "centre", c.values, 3);
      read_number(j, "size", c.values + 3);
      read_number(j, "points", c.values + 4);
      const json& axis = need(j, "axis");
      const std::string s = axis.is_string() ? axis.get<std::string>() : "";
      if (s.size() != 1 || s[0] < 'x' || s[0] > 'z') throw std::string("axis: expected x, y or z");
      c.values[5] = static_cast<float>(s[0] - 'x');
      break;
    }
    case SheetAction::kEdit: {
      const json& on = need(j, "on");
      if (!on.is_boolean()) throw std::string("on: expected true or false");
      c.values[0] = on.get<bool>() ? 1.0f : 0.0f;
      const json& inf = need(j, "influence");
      const std::string s = inf.is_string() ? inf.get<std::string>() : "";
      const auto it = std::find(kInfluenceNames.begin(), kInfluenceNames.end(), s);
      if (it == kInfluenceNames.end())
        throw std::string("influence: expected natural, gaussian or zone");
      c.values[1] = static_cast<float>(it - kInfluenceNames.begin());
      read_number(j, "radius", c.values + 2);
      break;
    }
    case SheetAction::kAdd:
    case SheetAction::kSubtract:
    case SheetAction::kTool:
      read_number(j, "thickness", c.values);
      break;
    case SheetAction::kRemove:
      break;
  }
}

SessionRecord parse_command(const json& j, int64_t t);
SessionRecord parse_haptic(const json& j, int64_t t);

// Reads one record line; throws std::string describing the problem.
SessionRecord parse_record(const json& j) {
  const json& tj = need(j, "t");
  if (!tj.is_number_integer()) throw std::string("t: expected integer nanoseconds");
  const int64_t t = tj.get<int64_t>();

  if (j.contains("cmd")) return parse_command(j, t);
  if (j.contains("haptic")) return parse_haptic(j, t);
  if (j.contains("report")) {
    if (!j["report"].is_string()) throw std::string("report: expected a hex string");
    const auto bytes = from_hex(j["report"].get<std::string>());
    if (!bytes) throw "report: '" + j["report"].get<std::string>() + "' is not hex";
    // No bytes is a report too: a tracker's "tracking lost" (the binary
    // format stores it alike).
    if (bytes->size() > hal::RawEvent::kMaxReportBytes) {
      throw std::string("report: expected 0 to 64 bytes");
    }
    SessionRecord r = SessionRecord::of(hal::RawEvent::report(t, *bytes));
    r.event.truncated = j.value("truncated", false);
    return r;
  }
  for (const char* key : {"axis", "button"}) {
    if (!j.contains(key)) continue;
    const json& a = j[key];
    if (!a.is_array() || a.size() != 2 || !a[0].is_number_integer() || !a[1].is_number_integer()) {
      throw std::string(key) + ": expected [index, value]";
    }
    const int index = a[0].get<int>();
    if (index < 0 || index > 63) throw std::string(key) + ": index out of range 0..63";
    return SessionRecord::of(key[0] == 'a' ? hal::RawEvent::axis(t, index, a[1].get<int>())
                                           : hal::RawEvent::button(t, index, a[1].get<int>() != 0));
  }
  if (j.contains("sync")) return SessionRecord::of(hal::RawEvent::sync(t));
  if (j.contains("removed")) return SessionRecord::of(hal::RawEvent::removed(t));
  throw std::string("expected one of report, axis, button, sync, removed, cmd, haptic");
}

// A true/false field as a command's choice: 1 or 0.
uint8_t read_bool(const json& j, const char* key) {
  const json& v = need(j, key);
  if (!v.is_boolean()) throw std::string(key) + ": expected true or false";
  return v.get<bool>() ? 1 : 0;
}

// An unsigned integer field of at most `max`.
template <class T>
T read_unsigned(const json& j, const char* key, uint64_t max) {
  const json& v = need(j, key);
  if (!v.is_number_unsigned() || v.get<uint64_t>() > max)
    throw std::string(key) + ": expected an integer 0.." + std::to_string(max);
  return static_cast<T>(v.get<uint64_t>());
}

SessionRecord parse_haptic(const json& j, int64_t t) {
  const json& name = j["haptic"];
  const auto type =
      name.is_string() ? parse_haptic_record_name(name.get<std::string>()) : std::nullopt;
  if (!type) throw std::string("haptic: unknown record ") + name.dump();
  HapticRecord h;
  h.type = *type;
  switch (h.type) {
    case HapticRecord::Type::kStart: {
      const json& v = need(j, "settings");
      if (!v.is_string()) throw std::string("settings: expected a string");
      h.settings = v.get<std::string>();
      break;
    }
    case HapticRecord::Type::kPatch:
      h.tag = read_unsigned<uint64_t>(j, "version", UINT64_MAX);
      read_numbers(j, "centre", h.values, 3);
      break;
    case HapticRecord::Type::kTick: {
      const json& tt = need(j, "tick_t");
      if (!tt.is_number_integer()) throw std::string("tick_t: expected integer nanoseconds");
      h.tick_t_ns = tt.get<int64_t>();
      h.index = read_unsigned<uint32_t>(j, "index", UINT32_MAX);
      h.buttons = read_unsigned<uint32_t>(j, "buttons", UINT32_MAX);
      h.flags = read_unsigned<uint8_t>(j, "flags", kTickFlagsMax);
      h.tag = read_unsigned<uint64_t>(j, "inputs", UINT64_MAX);
      read_numbers(j, "position_mm", h.values, 3);
      read_numbers(j, "force_n", h.values + 3, 3);
      break;
    }
  }
  if (auto why = haptic_problem(h))
    throw "haptic " + std::string(name.get<std::string>()) + ": " + *why;
  return SessionRecord::of(t, h);
}

SessionRecord parse_command(const json& j, int64_t t) {
  const json& name = j["cmd"];
  const auto kind = name.is_string() ? parse_command_name(name.get<std::string>()) : std::nullopt;
  if (!kind) throw std::string("cmd: unknown command ") + name.dump();
  Command c;
  c.kind = *kind;
  auto choice = [&](const char* key, auto parse) {
    const json& v = need(j, key);
    const auto parsed = v.is_string() ? parse(v.get<std::string>()) : std::nullopt;
    if (!parsed) throw std::string(key) + ": unknown value " + v.dump();
    c.choice = static_cast<uint8_t>(*parsed);
  };
  switch (c.kind) {
    case CommandKind::kTool:
      choice("shape", parse_tool_shape);
      read_numbers(j, "size", c.values, 2);
      break;
    case CommandKind::kMode:
      choice("mode", parse_sculpt_mode_id);
      break;
    case CommandKind::kStrength:
    case CommandKind::kSpacing:
    case CommandKind::kHardness:
    case CommandKind::kToolScale:
      read_number(j, "value", c.values);
      break;
    case CommandKind::kMirror: {
      choice("axis", [](const std::string& s) -> std::optional<uint8_t> {
        if (s == "off") return kMirrorOff;
        if (s.size() == 1 && s[0] >= 'x' && s[0] <= 'z') return static_cast<uint8_t>(s[0] - 'x');
        return std::nullopt;
      });
      read_number(j, "at", c.values);
      break;
    }
    case CommandKind::kVolume:
      read_numbers(j, "size", c.values, 3);
      c.choice = j.contains("clay_margin") ? kVolumeClay : kVolumeFill;
      read_number(j, c.choice == kVolumeClay ? "clay_margin" : "fill", c.values + 3);
      break;
    case CommandKind::kToolPose:
    case CommandKind::kPointer:
      read_numbers(j, "position", c.values, 3);
      read_numbers(j, "orientation", c.values + 3, 4);
      break;
    case CommandKind::kToolFromRegion:
      read_numbers(j, "lo", c.values, 3);
      read_numbers(j, "hi", c.values + 3, 3);
      break;
    case CommandKind::kHypertexture:
      read_numbers(j, "centre", c.values, 3);
      read_number(j, "radius", c.values + 3);
      read_number(j, "width", c.values + 4);
      read_number(j, "seed", c.values + 5);
      break;
    case CommandKind::kSheet:
      read_sheet(j, c);
      break;
    case CommandKind::kTouch:
    case CommandKind::kAccumulate:
      c.choice = read_bool(j, "on");
      break;
    case CommandKind::kClutch:
      c.choice = read_bool(j, "held");
      break;
    case CommandKind::kTracker:
      read_number(j, "scale_vox_per_mm", c.values);
      read_numbers(j, "rotation", c.values + 1, 4);
      break;
    case CommandKind::kToolVoxels: {
      auto tool = std::make_shared<ToolVoxels>();
      float dims[3];
      read_numbers(j, "dims", dims, 3);
      for (int a = 0; a < 3; ++a) {
        if (!(dims[a] >= 1.0f && dims[a] <= float(kMaxToolVoxelsEdge)) ||
            dims[a] != std::floor(dims[a]))
          throw std::string("dims: a side is a whole number from 1 to ") +
              std::to_string(kMaxToolVoxelsEdge);
        tool->dims[a] = static_cast<uint16_t>(dims[a]);
      }
      read_numbers(j, "pivot", tool->pivot, 3);
      read_number(j, "hardness", &tool->hardness);
      const json& d = need(j, "density");
      const auto bytes = d.is_string() ? from_hex(d.get<std::string>()) : std::nullopt;
      if (!bytes) throw std::string("density: expected a hex string");
      tool->density = *bytes;
      c.voxels = std::move(tool);
      break;
    }
    case CommandKind::kMorphology:
      choice("op", [](const std::string& s) -> std::optional<uint8_t> {
        if (s == "offset") return kMorphologyOffset;
        if (s == "close") return kMorphologyClose;
        return std::nullopt;
      });
      read_number(j, "by", c.values);
      break;
    default:
      break;
  }
  if (auto why = command_problem(c)) throw std::string(command_name(c.kind)) + ": " + *why;
  return SessionRecord::of(t, c);
}

}  // namespace

std::string session_to_text(const Session& session) {
  const hal::DeviceInfo& d = session.header.device;
  ordered header = {
      {"sculpt_session", kSessionVersion},
      {"device",
       {{"backend", text_field(d.backend)},
        {"path", text_field(d.path)},
        {"name", text_field(d.name)},
        {"manufacturer", text_field(d.manufacturer)},
        {"serial", text_field(d.serial)},
        {"vendor_product", d.vendor_product()},
        {"usage_page", d.usage_page},
        {"usage", d.usage},
        {"report_descriptor", to_hex(d.report_descriptor)}}},
      {"normalizer", text_field(session.header.normalizer_config)},
      {"created_unix_ns", session.header.created_unix_ns},
  };
  std::string out = header.dump() + "\n";
  for (const SessionRecord& r : session.records)
    out += record_json(r).dump() + "\n";
  return out;
}

Result<Session> session_from_text(std::string_view text, const std::string& name) {
  Session s;
  bool have_header = false;
  int64_t last_t = INT64_MIN;
  size_t line_no = 0;
  while (!text.empty()) {
    const size_t nl = text.find('\n');
    std::string_view line = text.substr(0, nl);
    text = nl == std::string_view::npos ? std::string_view() : text.substr(nl + 1);
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.find_first_not_of(" \t") == std::string_view::npos || line[0] == '#') continue;
    const std::string where = name + ":" + std::to_string(line_no) + ": ";
    const json j = json::parse(line, nullptr, /*allow_exceptions=*/false);
    if (j.is_discarded() || !j.is_object()) return Error(where + "not a JSON object");
    try {
      if (!have_header) {
        if (!j.contains("sculpt_session"))
          throw std::string("the first line must be the header (\"sculpt_session\")");
        if (j["sculpt_session"] != kSessionVersion)
          throw std::string("unsupported session version ") + j["sculpt_session"].dump();
        const json& d = j.at("device");
        hal::DeviceInfo& info = s.header.device;
        info.backend = read_text_field(d, "backend", kMaxBackendBytes);
        info.path = read_text_field(d, "path", kMaxDeviceTextBytes);
        info.name = read_text_field(d, "name", kMaxDeviceTextBytes);
        info.manufacturer = read_text_field(d, "manufacturer", kMaxDeviceTextBytes);
        info.serial = read_text_field(d, "serial", kMaxDeviceTextBytes);
        const std::string vp = d.value("vendor_product", "");
        unsigned vid = 0, pid = 0;
        char tail = 0;
        if (std::sscanf(vp.c_str(), "%4x:%4x%c", &vid, &pid, &tail) != 2) {
          throw "device.vendor_product: '" + vp + "' is not VVVV:PPPP hex";
        }
        info.vendor_id = static_cast<uint16_t>(vid);
        info.product_id = static_cast<uint16_t>(pid);
        info.usage_page = static_cast<uint16_t>(read_integer(d, "usage_page", 0, 0xFFFF));
        info.usage = static_cast<uint16_t>(read_integer(d, "usage", 0, 0xFFFF));
        const auto descriptor = from_hex(d.value("report_descriptor", ""));
        if (!descriptor) throw std::string("device.report_descriptor: not hex");
        if (descriptor->size() > kMaxDescriptorBytes) {
          throw "device.report_descriptor: " + std::to_string(descriptor->size()) +
              " bytes, more than the " + std::to_string(kMaxDescriptorBytes) + " a session holds";
        }
        info.report_descriptor = *descriptor;
        s.header.normalizer_config = read_text_field(j, "normalizer", kMaxNormalizerBytes);
        s.header.created_unix_ns = read_integer(j, "created_unix_ns", INT64_MIN, INT64_MAX);
        have_header = true;
        continue;
      }
      SessionRecord r = parse_record(j);
      if (r.t_ns() < last_t) throw std::string("t goes back in time");
      last_t = r.t_ns();
      s.records.push_back(r);
    } catch (const std::string& why) {
      return Error(where + why);
    } catch (const nlohmann::json::exception& e) {
      return Error(where + "malformed field (" + e.what() + ")");
    }
  }
  if (!have_header) return Error(name + ": empty session (no header line)");
  return s;
}

}  // namespace sculpt::sim
