#include "sculpt/sim/session/command_limits.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace sculpt::sim {
namespace {

// A number as a message shows it: shortest form, printable.
std::string number(float v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", double(v));
  return text;
}

}  // namespace

std::optional<std::string> command_problem(const Command& c) {
  const int n = Command::value_count(c.kind);
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(c.values[i]))
      return "value " + std::to_string(i) + " is not a finite number";
  const auto in = [](float v, float lo, float hi) { return v >= lo && v <= hi; };
  const auto coordinates = [&](int first, int count) -> std::optional<std::string> {
    for (int i = first; i < first + count; ++i)
      if (!in(c.values[i], -kMaxCoordinateVox, kMaxCoordinateVox))
        return "coordinate " + number(c.values[i]) + " is beyond +-" + number(kMaxCoordinateVox) +
               " voxels";
    return std::nullopt;
  };
  const auto choice_below = [&](int count, const char* what) -> std::optional<std::string> {
    if (c.choice >= count) return std::string(what) + " " + std::to_string(c.choice) + " unknown";
    return std::nullopt;
  };
  switch (c.kind) {
    case CommandKind::kTool:
      if (auto why = choice_below(kToolShapeCount, "tool shape")) return why;
      {
        // A sphere and a cube have one size (the second is 0); the others two.
        const auto shape = static_cast<ToolShape>(c.choice);
        const int sizes = shape == ToolShape::kSphere || shape == ToolShape::kCube ? 1 : 2;
        for (int i = 0; i < 2; ++i) {
          const bool unused = i >= sizes && c.values[i] == 0.0f;
          if (!unused && !(c.values[i] > 0.0f && c.values[i] <= kMaxToolSizeVox))
            return "tool size " + number(c.values[i]) + " is outside (0, " +
                   number(kMaxToolSizeVox) + "] voxels";
        }
        return std::nullopt;
      }
    case CommandKind::kMode:
      return choice_below(kSculptModeCount, "sculpt mode");
    case CommandKind::kStrength:
      if (!in(c.values[0], 0.0f, 1.0f))
        return "strength " + number(c.values[0]) + " is outside [0, 1]";
      return choice_below(1, "choice");
    case CommandKind::kHardness:
      if (!in(c.values[0], 0.0f, 1.0f))
        return "hardness " + number(c.values[0]) + " is outside [0, 1]";
      return choice_below(1, "choice");
    case CommandKind::kToolScale:
      if (!in(c.values[0], kMinToolScale, kMaxToolScale))
        return "tool scale " + number(c.values[0]) + " is outside [" + number(kMinToolScale) +
               ", " + number(kMaxToolScale) + "]";
      return choice_below(1, "choice");
    case CommandKind::kMorphology:
      if (auto why = choice_below(2, "morphology")) return why;
      if (c.choice == kMorphologyOffset && !in(c.values[0], -kMaxMorphologyVox, kMaxMorphologyVox))
        return "offset " + number(c.values[0]) + " is outside [-" + number(kMaxMorphologyVox) +
               ", " + number(kMaxMorphologyVox) + "] voxels";
      if (c.choice == kMorphologyClose && !(c.values[0] > 0.0f && c.values[0] <= kMaxMorphologyVox))
        return "closing radius " + number(c.values[0]) + " is outside (0, " +
               number(kMaxMorphologyVox) + "] voxels";
      return std::nullopt;
    case CommandKind::kSpacing:
      if (!(c.values[0] > 0.0f && c.values[0] <= kMaxSpacing))
        return "spacing " + number(c.values[0]) + " is outside (0, " + number(kMaxSpacing) + "]";
      return choice_below(1, "choice");
    case CommandKind::kMirror:
      if (c.choice > 2 && c.choice != kMirrorOff)
        return "mirror axis " + std::to_string(c.choice) + " unknown";
      return coordinates(0, 1);
    case CommandKind::kVolume: {
      if (auto why = choice_below(2, "volume kind")) return why;
      double voxels = 1.0;
      for (int i = 0; i < 3; ++i) {
        const float side = c.values[i];
        if (!(side >= 1.0f && side <= kMaxCoordinateVox) || side != std::floor(side))
          return "volume side " + number(side) + " is not a whole number of voxels from 1";
        voxels *= double(side);
      }
      if (voxels > kMaxVolumeVoxels)
        return "volume of " + number(float(voxels)) + " voxels is over the limit of 2^32";
      if (c.choice == kVolumeFill && !in(c.values[3], 0.0f, 255.0f))
        return "fill density " + number(c.values[3]) + " is outside [0, 255]";
      if (c.choice == kVolumeClay && !in(c.values[3], 0.0f, kMaxCoordinateVox))
        return "clay margin " + number(c.values[3]) + " is negative or too large";
      return std::nullopt;
    }
    case CommandKind::kToolPose:
    case CommandKind::kPointer: {
      if (auto why = coordinates(0, 3)) return why;
      float norm2 = 0.0f;
      for (int i = 3; i < 7; ++i)
        norm2 += c.values[i] * c.values[i];
      if (!(norm2 > 1e-12f && norm2 < 1e12f)) return "orientation is not a rotation";
      return choice_below(1, "choice");
    }
    case CommandKind::kToolFromRegion:
      if (auto why = coordinates(0, 6)) return why;
      for (int i = 0; i < 3; ++i)
        if (c.values[i + 3] - c.values[i] > 2.0f * kMaxToolSizeVox + 1.0f)
          return "region side " + number(c.values[i + 3] - c.values[i]) + " is over " +
                 number(2.0f * kMaxToolSizeVox + 1.0f) + " voxels, the largest tool";
      return choice_below(1, "choice");
    case CommandKind::kHypertexture:
      if (auto why = coordinates(0, 3)) return why;
      if (!in(c.values[3], 0.0f, kMaxCoordinateVox) || !in(c.values[4], 0.0f, kMaxCoordinateVox))
        return "hypertexture radius or width is negative or too large";
      return choice_below(1, "choice");
    case CommandKind::kSheet: {
      if (auto why = choice_below(kSheetActionCount, "sheet action")) return why;
      const auto action = static_cast<SheetAction>(c.choice);
      if (action == SheetAction::kPlace) {
        if (auto why = coordinates(0, 4)) return why;
        if (c.values[5] != 0.0f && c.values[5] != 1.0f && c.values[5] != 2.0f)
          return "sheet axis " + number(c.values[5]) + " is not 0, 1 or 2";
      }
      if (action == SheetAction::kEdit && c.values[1] != 0.0f && c.values[1] != 1.0f &&
          c.values[1] != 2.0f)
        return "sheet influence " + number(c.values[1]) + " is not 0, 1 or 2";
      return std::nullopt;
    }
    case CommandKind::kTouch:
      return choice_below(2, "touch");
    case CommandKind::kAccumulate:
      return choice_below(2, "accumulate");
    case CommandKind::kClutch:
      return choice_below(2, "clutch");
    case CommandKind::kTracker: {
      if (!in(c.values[0], kMinTrackerScale, kMaxTrackerScale))
        return "tracker scale " + number(c.values[0]) + " is outside [" + number(kMinTrackerScale) +
               ", " + number(kMaxTrackerScale) + "] voxels per mm";
      // A unit quaternion, to float precision: any other would scale the
      // motion as well as turn it.
      float norm2 = 0.0f;
      for (int i = 1; i < 5; ++i)
        norm2 += c.values[i] * c.values[i];
      if (!(std::abs(norm2 - 1.0f) < 1e-3f)) return "tracker rotation is not a unit quaternion";
      return choice_below(1, "choice");
    }
    case CommandKind::kToolVoxels:
      if (c.voxels == nullptr) return "no voxels";
      if (auto why = tool_voxels_problem(*c.voxels)) return why;
      return choice_below(1, "choice");
    case CommandKind::kPress:
    case CommandKind::kRelease:
    case CommandKind::kUndo:
    case CommandKind::kRedo:
      return choice_below(1, "choice");
  }
  return "unknown command";
}

std::optional<std::string> tool_voxels_problem(const ToolVoxels& t) {
  size_t voxels = 1;
  for (int a = 0; a < 3; ++a) {
    if (t.dims[a] < 1 || t.dims[a] > kMaxToolVoxelsEdge)
      return "tool side " + std::to_string(t.dims[a]) + " is outside [1, " +
             std::to_string(kMaxToolVoxelsEdge) + "] voxels";
    voxels *= t.dims[a];
    const float edge = static_cast<float>(t.dims[a]);
    if (!std::isfinite(t.pivot[a]) || t.pivot[a] < -edge || t.pivot[a] > 2.0f * edge)
      return "tool pivot " + number(t.pivot[a]) + " is more than the grid's size outside it";
  }
  if (t.density.size() != voxels)
    return "tool of " + std::to_string(t.density.size()) + " voxels where its sides make " +
           std::to_string(voxels);
  if (!(t.hardness >= 0.0f && t.hardness <= 1.0f))
    return "tool hardness " + number(t.hardness) + " is outside [0, 1]";
  return std::nullopt;
}

std::optional<std::string> haptic_problem(const HapticRecord& h) {
  using Type = HapticRecord::Type;
  if (h.type < Type::kStart || h.type > Type::kTick) return "unknown haptic record";
  if (h.settings.size() > kMaxHapticSettingsBytes) return "set-up text longer than 4096 bytes";
  for (float v : h.values)
    if (!std::isfinite(v) || std::abs(v) > kMaxCoordinateVox) return "value out of range";
  if (h.type == Type::kStart) {
    const auto parsed = parse_haptic_settings(h.settings);
    if (const auto* why = std::get_if<std::string>(&parsed)) return "set-up text: " + *why;
  }
  if (h.type != Type::kTick) return std::nullopt;
  const int read = (h.flags >> kTickReadShift) & 3;
  const int request = h.flags >> kTickRequestShift;
  if (read > 2 || request > 2) return "unknown tick flags";
  return std::nullopt;
}

Status check_writable(const SessionRecord& r, const std::string& name, int64_t index) {
  if (r.kind == SessionRecord::Kind::kHaptic) {
    const auto why = haptic_problem(r.haptic);
    if (!why) return {};
    return Error(name + ": record " + std::to_string(index) + ": haptic " +
                 std::string(haptic_record_name(r.haptic.type)) + ": " + *why + "; not written");
  }
  if (r.kind != SessionRecord::Kind::kCommand) return {};
  const auto why = command_problem(r.command);
  if (!why) return {};
  return Error(name + ": record " + std::to_string(index) + ": " +
               std::string(command_name(r.command.kind)) + ": " + *why + "; not written");
}

}  // namespace sculpt::sim
