#pragma once
// A recorded session in memory (DESIGN.md §6): the device it came from, the
// normaliser settings in force, and every raw device event and station command
// with its time, in time order. The binary file (session_file.h) and the text
// form (session_text.h) both hold exactly this.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
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
  kMode,       ///< choice = SculptModeId (a mode, or a ball brush from kClay on)
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
  /// The clutch: choice 1 held, 0 let go. While held the device moves
  /// without moving the tool; a tracker re-anchors where the tool is when it
  /// is let go, so a small reach covers a whole sculpture.
  kClutch,
  /// How a tracker's space maps to the sculpture (hal::TrackerCalibration):
  /// values[0] voxels per millimetre of tracker motion, values[1..4] the
  /// rotation from tracker axes to the sculpture's as a unit quaternion
  /// w x y z. The tracker re-anchors where the tool is.
  kTracker,
  /// The built-in tools' hardness (core::Tool::hardness): values[0] in
  /// [0, 1], 1 the hard edge, 0 a smooth bump (its falloff over the tool).
  kHardness,
  /// Swept strokes build up where they overlap themselves: choice 1 on, 0
  /// off (core::StrokeOptions::accumulate; off, a stroke applies its
  /// strength once per voxel).
  kAccumulate,
  /// A custom tool (a region, the sculpture, the sheet's shell, a file) at
  /// another size: values[0] the factor in [0.125, 8] from the size it was
  /// made at (1: as made), resampled trilinearly (core::scale_tool). Ignored
  /// while the tool is a built-in shape (kTool sizes those).
  kToolScale,
  /// The sculpture's surface moved on its sub-voxel distance field (Jones &
  /// Satherley §4.2): choice kMorphologyOffset, values[0] the distance in
  /// voxels (> 0 outward, < 0 inward); choice kMorphologyClose, values[0]
  /// the closing radius in voxels. One undo step.
  kMorphology,
  /// A tool given whole (a tool file loaded, a mesh imported): its voxels
  /// ride in Command::voxels (no values), so a replay holds the same tool.
  /// The binary file stores it as tool records of its own (session_file.h).
  kToolVoxels,
};
inline constexpr uint8_t kCommandKindCount = 23;
static_assert(static_cast<uint8_t>(CommandKind::kToolVoxels) == kCommandKindCount,
              "a new command kind: add its name and value count in session.cpp");
inline constexpr uint8_t kMorphologyOffset = 0;
inline constexpr uint8_t kMorphologyClose = 1;
inline constexpr uint8_t kVolumeFill = 0;
inline constexpr uint8_t kVolumeClay = 1;

enum class ToolShape : uint8_t { kSphere, kCube, kCylinder, kRing, kCone };
inline constexpr uint8_t kToolShapeCount = 5;
/// The first five in the order of sculpt::core::SculptMode; from kClay on
/// the ball brushes (core/sculpt/*_brush.h), which the station applies to a
/// press's whole path when it ends. Values are stored in sessions and
/// projects: only ever append.
enum class SculptModeId : uint8_t {
  kAdd,
  kSubtract,
  kUnion,
  kDifference,
  kSmooth,
  kClay,
  kFlatten,
  kInflate,
  kPinch,
  kGrab,
};
inline constexpr uint8_t kSculptModeCount = 10;
/// The first ball brush's id: ids below it are core::SculptMode's.
inline constexpr uint8_t kFirstBallBrushMode = 5;
static_assert(static_cast<uint8_t>(SculptModeId::kClay) == kFirstBallBrushMode);
static_assert(static_cast<uint8_t>(SculptModeId::kGrab) + 1 == kSculptModeCount);
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

/// A tool's voxels as a session carries them (kToolVoxels): the station's
/// core::Tool without core.
struct ToolVoxels {
  uint16_t dims[3] = {0, 0, 0};
  float pivot[3] = {};  ///< voxel index units, voxel centres at integers
  float hardness = 1.0f;
  std::vector<uint8_t> density;  ///< dims[0] * dims[1] * dims[2], x fastest

  friend bool operator==(const ToolVoxels& a, const ToolVoxels& b);
};
/// The largest tool a session carries, voxels a side (as many as the
/// largest scaled tool, and room to spare).
inline constexpr uint32_t kMaxToolVoxelsEdge = 256;

struct Command {
  CommandKind kind = CommandKind::kPress;
  uint8_t choice = 0;
  float values[7] = {};
  /// kToolVoxels: the tool (shared: records are copied freely). Null otherwise.
  std::shared_ptr<const ToolVoxels> voxels = nullptr;

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

/// A force device's haptic loop (DESIGN.md §5a), recorded so that a replay
/// can run it again tick by tick. The sim module keeps the numbers; the
/// station gives them meaning (station/haptics/haptic_recording.h).
struct HapticRecord {
  enum class Type : uint8_t {
    kStart = 1,  ///< a loop starts: `settings` holds how it is set up
    kPatch,      ///< the sculpting side published a patch to the loop
    kTick,       ///< one tick of the loop
  };
  Type type = Type::kTick;
  /// kStart: the loop's set-up in the station's text form.
  std::string settings;
  /// kPatch: the patch's version; kTick: what the force law read besides
  /// the device (hal::ForceLaw::inputs()).
  uint64_t tag = 0;
  /// kTick: the tick's own time (the record's time is when the sculpting
  /// side took it from the loop), its number in its loop, the buttons, and
  /// kTickHomed | read << kTickReadShift | request << kTickRequestShift.
  int64_t tick_t_ns = 0;
  uint32_t index = 0;
  uint32_t buttons = 0;
  uint8_t flags = 0;
  /// kPatch: the centre asked for, voxels. kTick: position mm (0..2) and
  /// the force written, N (3..5).
  float values[6] = {};

  friend bool operator==(const HapticRecord& a, const HapticRecord& b);
};
inline constexpr uint8_t kTickHomed = 1;
inline constexpr int kTickReadShift = 1;     ///< 0 ok, 1 removed, 2 fault
inline constexpr int kTickRequestShift = 3;  ///< 0 none, 1 enable, 2 drop
inline constexpr uint8_t kTickFlagsMax = 2 << kTickRequestShift | 3 << kTickReadShift | kTickHomed;
/// The longest loop set-up text, bytes.
inline constexpr size_t kMaxHapticSettingsBytes = 4096;
/// A loop's set-up text: "name = number" lines, names of [a-z0-9_.], numbers
/// finite (written with 17 digits, so they read back bit for bit).
using HapticSettings = std::vector<std::pair<std::string, double>>;
std::string haptic_settings_text(const HapticSettings& settings);
/// The settings, or why the text is not set-up text (the line and the problem).
std::variant<HapticSettings, std::string> parse_haptic_settings(std::string_view text);
std::string_view haptic_record_name(HapticRecord::Type type);
std::optional<HapticRecord::Type> parse_haptic_record_name(std::string_view name);

struct SessionRecord {
  enum class Kind : uint8_t { kEvent, kCommand, kHaptic };
  Kind kind = Kind::kEvent;
  hal::RawEvent event;       ///< kEvent (its t_ns is the record's time)
  Command command;           ///< kCommand
  HapticRecord haptic;       ///< kHaptic
  int64_t command_t_ns = 0;  ///< the time of a kCommand or kHaptic record

  int64_t t_ns() const { return kind == Kind::kEvent ? event.t_ns : command_t_ns; }
  static SessionRecord of(const hal::RawEvent& e);
  static SessionRecord of(int64_t t_ns, const Command& c);
  static SessionRecord of(int64_t t_ns, const HapticRecord& h);
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
