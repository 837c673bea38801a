#pragma once
// A recorded session in memory (DESIGN.md §6): the device it came from, the
// normaliser settings in force, and every raw device event and station command
// with its time, in time order. The binary file (session_file.h) and the text
// form (session_text.h) both hold exactly this.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sculpt/hal/types/device_info.h"
#include "sculpt/hal/types/raw_event.h"

namespace sculpt::sim {

/// Station commands a session records next to the device's reports. The sim
/// module knows them by name only; the station gives them meaning.
enum class CommandKind : uint8_t {
  kPress = 1,  ///< the tool goes down: a stroke starts
  kRelease,    ///< the tool comes up: the stroke ends
  kTool,       ///< shape + size: choice = ToolShape, values[0..1] = sizes in voxels
  kMode,       ///< choice = SculptModeId
  kStrength,   ///< values[0] in [0, 1]
  kSpacing,    ///< values[0]: dab spacing as a fraction of the tool's size, > 0
  kMirror,     ///< choice = axis 0..2, or kMirrorOff; values[0] = plane position, voxels
  kUndo,
  kRedo,
  /// A new block: values[0..2] = size in voxels; choice kVolumeFill: values[3]
  /// = density of every voxel; choice kVolumeClay: a slab of clay fills the
  /// block but for a margin of values[3] voxels on every side.
  kVolume,
  kToolPose,  ///< places the tool: values[0..2] position (voxels), values[3..6] w x y z
  /// The ordinary mouse or keyboard moved the tool: values as kToolPose, but a
  /// stroke in progress goes on (dabs are sampled along the move).
  kPointer,
  /// The material in a box becomes the tool (pivot at the box's centre):
  /// values[0..2] low corner, values[3..5] high corner (voxels, half-open).
  kToolFromRegion,
  /// A hypertexture skin (Jones & Satherley §4.3) baked around the surface:
  /// values[0..2] centre, values[3] radius of the region, values[4] width of
  /// the soft region (voxels), values[5] noise seed.
  kHypertexture,
  /// The NURBS sheet: choice = SheetAction (see there for the values).
  kSheet,
  /// Touch mode for devices without force output: choice 1 on, 0 off (the
  /// tool stops on the material and presses in as the cap is pushed).
  kTouch,
};
inline constexpr uint8_t kCommandKindCount = 16;
inline constexpr uint8_t kVolumeFill = 0;
inline constexpr uint8_t kVolumeClay = 1;

enum class ToolShape : uint8_t { kSphere, kCube, kCylinder, kRing, kCone };
inline constexpr uint8_t kToolShapeCount = 5;
/// The order of sculpt::core::SculptMode.
enum class SculptModeId : uint8_t { kAdd, kSubtract, kUnion, kDifference, kSmooth };
inline constexpr uint8_t kSculptModeCount = 5;
inline constexpr uint8_t kMirrorOff = 255;

/// What a kSheet command does, and its values.
enum class SheetAction : uint8_t {
  /// A flat bicubic sheet: values[0..2] centre, values[3] size (voxels),
  /// values[4] control points a side, values[5] normal axis 0..2.
  kPlace,
  kRemove,
  /// Device presses grab the sheet instead of sculpting: values[0] 1 on, 0
  /// off; values[1] influence (0 natural, 1 gaussian, 2 zone); values[2]
  /// its radius (control points for gaussian, parameter units for zone).
  kEdit,
  /// The sheet's shell of thickness values[0] voxels added to or subtracted
  /// from the material, or made the tool.
  kAdd,
  kSubtract,
  kTool,
};
inline constexpr uint8_t kSheetActionCount = 6;

struct Command {
  CommandKind kind = CommandKind::kPress;
  uint8_t choice = 0;
  float values[7] = {};

  /// Number of values[] the kind uses.
  static int value_count(CommandKind kind);
  friend bool operator==(const Command& a, const Command& b);
};

/// Names used by the text form and messages: "press", "tool", ...
std::string_view command_name(CommandKind kind);
std::optional<CommandKind> parse_command_name(std::string_view name);
std::string_view tool_shape_name(ToolShape shape);
std::optional<ToolShape> parse_tool_shape(std::string_view name);
std::string_view sculpt_mode_name(SculptModeId mode);
std::optional<SculptModeId> parse_sculpt_mode_id(std::string_view name);
std::string_view sheet_action_name(SheetAction action);
std::optional<SheetAction> parse_sheet_action(std::string_view name);

struct SessionRecord {
  enum class Kind : uint8_t { kEvent, kCommand };
  Kind kind = Kind::kEvent;
  hal::RawEvent event;  ///< kEvent (its t_ns is the record's time)
  Command command;      ///< kCommand
  int64_t command_t_ns = 0;

  int64_t t_ns() const { return kind == Kind::kEvent ? event.t_ns : command_t_ns; }
  static SessionRecord of(const hal::RawEvent& e);
  static SessionRecord of(int64_t t_ns, const Command& c);
  friend bool operator==(const SessionRecord& a, const SessionRecord& b);
};

/// What a session file's header holds at most (session_file.cpp reads no
/// more); the text form refuses more, so whatever it accepts converts to a
/// file and back. Bytes.
inline constexpr uint32_t kMaxHeaderBytes = 1u << 20;  ///< the whole header
inline constexpr uint32_t kMaxBackendBytes = 256;
inline constexpr uint32_t kMaxDeviceTextBytes = 4096;  ///< path, name, manufacturer, serial
inline constexpr uint32_t kMaxDescriptorBytes = 4096;
/// The rest of the header fits in the 64 KiB left beside it.
inline constexpr uint32_t kMaxNormalizerBytes = kMaxHeaderBytes - (1u << 16);

struct SessionHeader {
  /// The device (backend, path, name, vendor:product, serial, report descriptor).
  hal::DeviceInfo device;
  /// The normaliser settings in force, in hal::to_text(NormalizerConfig) form.
  std::string normalizer_config;
  /// Wall-clock time the recording started, ns since the Unix epoch (0 = unknown).
  int64_t created_unix_ns = 0;
};

struct Session {
  SessionHeader header;
  std::vector<SessionRecord> records;

  /// Time of the first and last record (0 when empty).
  int64_t start_t_ns() const { return records.empty() ? 0 : records.front().t_ns(); }
  int64_t end_t_ns() const { return records.empty() ? 0 : records.back().t_ns(); }
};

bool operator==(const SessionHeader& a, const SessionHeader& b);
bool operator==(const Session& a, const Session& b);

}  // namespace sculpt::sim
