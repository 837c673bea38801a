#pragma once
// Limits the ball brushes (smooth, clay, flatten, inflate, pinch, grab)
// check their options against.

namespace sculpt::core {

/// Largest ball radius a brush accepts, in voxels: the largest built-in tool
/// (sim::kMaxToolSizeVox), so a brush reaches no farther than a tool.
inline constexpr float kMaxBrushRadiusVox = 256.0f;

}  // namespace sculpt::core
