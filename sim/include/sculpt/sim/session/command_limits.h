#pragma once
// The ranges a session's commands must keep, checked by both readers (the
// binary file and the text form) before a command reaches the station: a
// record whose CRC holds can still carry a choice no name table has, a NaN,
// or a size that would take all the machine's memory.

#include <optional>
#include <string>

#include "sculpt/base/result.h"
#include "sculpt/sim/session/session.h"

namespace sculpt::sim {

/// Tool sizes (a radius, an edge, a height) in voxels: a 513^3 tool grid at
/// most (135 MB).
inline constexpr float kMaxToolSizeVox = 256.0f;
/// A custom tool's scale (kToolScale): core::kMinToolScale..kMaxToolScale.
inline constexpr float kMinToolScale = 0.125f;
inline constexpr float kMaxToolScale = 8.0f;
/// Offset distance and closing radius of a kMorphology command, voxels.
inline constexpr float kMaxMorphologyVox = 64.0f;
/// Positions, plane positions and volume sides, in voxels.
inline constexpr float kMaxCoordinateVox = 1048576.0f;
/// A new volume's voxels.
inline constexpr double kMaxVolumeVoxels = 4294967296.0;
/// Dab spacing, as a fraction of the tool's size.
inline constexpr float kMaxSpacing = 16.0f;
/// A tracker's scale, voxels per millimetre: from a 256-voxel block spread
/// over 256 m of motion to one over a quarter of a millimetre.
inline constexpr float kMinTrackerScale = 0.001f;
inline constexpr float kMaxTrackerScale = 1000.0f;

/// What is wrong with `c`, in a few words; nothing when it is in range.
std::optional<std::string> command_problem(const Command& c);

/// What is wrong with a tool's voxels (a side of 0 or over
/// kMaxToolVoxelsEdge, a density of another size, a pivot not finite or more
/// than the grid's size outside it, a hardness outside [0, 1]).
std::optional<std::string> tool_voxels_problem(const ToolVoxels& t);

/// What is wrong with a haptic record (an unknown type or flag, a value
/// that is not finite, set-up text too long); nothing when it is sound.
std::optional<std::string> haptic_problem(const HapticRecord& h);

/// The writers' side: a command or haptic record the readers would refuse is an error
/// naming `name` and the record's `index`, so a file we write always opens.
Status check_writable(const SessionRecord& r, const std::string& name, int64_t index);

}  // namespace sculpt::sim
