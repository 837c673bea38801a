#include "sculpt/sim/session/session.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace sculpt::sim {
namespace {

constexpr std::array<std::string_view, kCommandKindCount> kCommandNames = {"press",
                                                                           "release",
                                                                           "tool",
                                                                           "mode",
                                                                           "strength",
                                                                           "spacing",
                                                                           "mirror",
                                                                           "undo",
                                                                           "redo",
                                                                           "volume",
                                                                           "tool_pose",
                                                                           "pointer",
                                                                           "tool_from_region",
                                                                           "hypertexture",
                                                                           "sheet",
                                                                           "touch",
                                                                           "clutch",
                                                                           "tracker",
                                                                           "hardness",
                                                                           "accumulate",
                                                                           "tool_scale",
                                                                           "morphology",
                                                                           "tool_voxels"};
// Every kind has a name and a value count (std::array fills missing ones silently).
static_assert(!kCommandNames.back().empty(), "a new command kind needs its name here");
constexpr std::array<int, kCommandKindCount> kValueCounts = {0, 0, 2, 0, 1, 1, 1, 0, 0, 4, 7, 7,
                                                             6, 6, 6, 0, 0, 5, 1, 0, 1, 1, 0};
constexpr std::array<std::string_view, kToolShapeCount> kShapeNames = {"sphere", "cube", "cylinder",
                                                                       "ring", "cone"};
constexpr std::array<std::string_view, kSculptModeCount> kModeNames = {
    "add",  "subtract", "union",   "difference", "smooth",
    "clay", "flatten",  "inflate", "pinch",      "grab"};
constexpr std::array<std::string_view, kSheetActionCount> kSheetActionNames = {
    "place", "remove", "edit", "add", "subtract", "tool"};
constexpr std::array<std::string_view, 3> kHapticRecordNames = {"start", "patch", "tick"};

template <size_t N>
std::optional<uint8_t> find_name(const std::array<std::string_view, N>& names,
                                 std::string_view name) {
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) return std::nullopt;
  return static_cast<uint8_t>(it - names.begin());
}

bool same_event(const hal::RawEvent& a, const hal::RawEvent& b) {
  return a.kind == b.kind && a.t_ns == b.t_ns && a.size == b.size && a.truncated == b.truncated &&
         a.index == b.index && a.value == b.value &&
         std::equal(a.data.begin(), a.data.begin() + a.size, b.data.begin());
}

}  // namespace

int Command::value_count(CommandKind kind) {
  return kValueCounts[static_cast<size_t>(kind) - 1];
}

bool operator==(const Command& a, const Command& b) {
  // Bitwise on the used values: a replayed command must be the recorded one.
  const int n = Command::value_count(a.kind);
  if (a.kind == CommandKind::kToolVoxels &&
      (a.voxels == nullptr || b.voxels == nullptr ? a.voxels != b.voxels
                                                  : !(*a.voxels == *b.voxels)))
    return false;
  return a.kind == b.kind && a.choice == b.choice &&
         std::memcmp(a.values, b.values, sizeof(float) * static_cast<size_t>(n)) == 0;
}

bool operator==(const ToolVoxels& a, const ToolVoxels& b) {
  // Bitwise, as the commands' values.
  return std::memcmp(a.dims, b.dims, sizeof a.dims) == 0 &&
         std::memcmp(a.pivot, b.pivot, sizeof a.pivot) == 0 &&
         std::memcmp(&a.hardness, &b.hardness, sizeof a.hardness) == 0 && a.density == b.density;
}

std::string_view command_name(CommandKind kind) {
  return kCommandNames[static_cast<size_t>(kind) - 1];
}
std::optional<CommandKind> parse_command_name(std::string_view name) {
  const auto i = find_name(kCommandNames, name);
  return i ? std::optional(static_cast<CommandKind>(*i + 1)) : std::nullopt;
}
std::string_view tool_shape_name(ToolShape shape) {
  return kShapeNames[static_cast<size_t>(shape)];
}
std::optional<ToolShape> parse_tool_shape(std::string_view name) {
  const auto i = find_name(kShapeNames, name);
  return i ? std::optional(static_cast<ToolShape>(*i)) : std::nullopt;
}
std::string_view sculpt_mode_name(SculptModeId mode) {
  return kModeNames[static_cast<size_t>(mode)];
}
std::optional<SculptModeId> parse_sculpt_mode_id(std::string_view name) {
  const auto i = find_name(kModeNames, name);
  return i ? std::optional(static_cast<SculptModeId>(*i)) : std::nullopt;
}

std::string_view sheet_action_name(SheetAction action) {
  const auto i = static_cast<size_t>(action);
  return i < kSheetActionNames.size() ? kSheetActionNames[i] : "unknown";
}
std::optional<SheetAction> parse_sheet_action(std::string_view name) {
  const auto i = find_name(kSheetActionNames, name);
  return i ? std::optional(static_cast<SheetAction>(*i)) : std::nullopt;
}

SessionRecord SessionRecord::of(const hal::RawEvent& e) {
  SessionRecord r;
  r.kind = Kind::kEvent;
  r.event = e;
  return r;
}

SessionRecord SessionRecord::of(int64_t t_ns, const Command& c) {
  SessionRecord r;
  r.kind = Kind::kCommand;
  r.command = c;
  r.command_t_ns = t_ns;
  return r;
}

SessionRecord SessionRecord::of(int64_t t_ns, const HapticRecord& h) {
  SessionRecord r;
  r.kind = Kind::kHaptic;
  r.haptic = h;
  r.command_t_ns = t_ns;
  return r;
}

bool operator==(const HapticRecord& a, const HapticRecord& b) {
  return a.type == b.type && a.settings == b.settings && a.tag == b.tag &&
         a.tick_t_ns == b.tick_t_ns && a.index == b.index && a.buttons == b.buttons &&
         a.flags == b.flags && std::memcmp(a.values, b.values, sizeof a.values) == 0;
}

std::string haptic_settings_text(const HapticSettings& settings) {
  std::string out;
  char number[32];
  for (const auto& [name, value] : settings) {
    std::snprintf(number, sizeof number, "%.17g", value);
    out += name + " = " + number + "\n";
  }
  return out;
}

std::variant<HapticSettings, std::string> parse_haptic_settings(std::string_view text) {
  HapticSettings settings;
  int line_number = 0;
  while (!text.empty()) {
    ++line_number;
    const size_t end = std::min(text.find('\n'), text.size());
    const std::string line(text.substr(0, end));
    text.remove_prefix(std::min(end + 1, text.size()));
    if (line.empty()) continue;
    const std::string where = "line " + std::to_string(line_number) + ": ";
    const size_t eq = line.find(" = ");
    if (eq == std::string::npos || eq == 0) return where + "expected \"name = number\"";
    const std::string name = line.substr(0, eq);
    const bool name_ok = std::all_of(name.begin(), name.end(), [](char c) {
      return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '.';
    });
    if (!name_ok) return where + "a name holds only a-z, 0-9, _ and .";
    const std::string value = line.substr(eq + 3);
    char* rest = nullptr;
    const double v = std::strtod(value.c_str(), &rest);
    if (value.empty() || rest != value.c_str() + value.size() || !std::isfinite(v))
      return where + name + ": not a finite number";
    settings.emplace_back(name, v);
  }
  return settings;
}

std::string_view haptic_record_name(HapticRecord::Type type) {
  return kHapticRecordNames[static_cast<size_t>(type) - 1];
}

std::optional<HapticRecord::Type> parse_haptic_record_name(std::string_view name) {
  const auto i = find_name(kHapticRecordNames, name);
  return i ? std::optional(static_cast<HapticRecord::Type>(*i + 1)) : std::nullopt;
}

bool operator==(const SessionRecord& a, const SessionRecord& b) {
  if (a.kind != b.kind) return false;
  switch (a.kind) {
    case SessionRecord::Kind::kEvent:
      return same_event(a.event, b.event);
    case SessionRecord::Kind::kCommand:
      return a.command_t_ns == b.command_t_ns && a.command == b.command;
    case SessionRecord::Kind::kHaptic:
      return a.command_t_ns == b.command_t_ns && a.haptic == b.haptic;
  }
  return false;
}

bool operator==(const SessionHeader& a, const SessionHeader& b) {
  const hal::DeviceInfo& x = a.device;
  const hal::DeviceInfo& y = b.device;
  return x.backend == y.backend && x.path == y.path && x.name == y.name &&
         x.manufacturer == y.manufacturer && x.serial == y.serial && x.vendor_id == y.vendor_id &&
         x.product_id == y.product_id && x.usage_page == y.usage_page && x.usage == y.usage &&
         x.report_descriptor == y.report_descriptor && a.normalizer_config == b.normalizer_config &&
         a.created_unix_ns == b.created_unix_ns;
}

bool operator==(const Session& a, const Session& b) {
  return a.header == b.header && a.records == b.records;
}

}  // namespace sculpt::sim
