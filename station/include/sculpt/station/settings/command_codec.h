#pragma once
// The one place a session command's choice byte becomes a core enum and
// back. Sessions store sim::SculptModeId and sim::ToolShape (the file
// format's own enums, which sim keeps without depending on core); the
// station sculpts with core::SculptMode. The lists must keep the same order
// for a recorded session to keep meaning what it meant: checked here at
// compile time, and every conversion range-checks instead of casting.

#include <cstdint>
#include <optional>

#include "sculpt/core/sculpt/sculptor.h"
#include "sculpt/core/tool/tool.h"
#include "sculpt/sim/session/session.h"
#include "sculpt/station/settings/station_settings.h"

namespace sculpt::station {

namespace codec_detail {
constexpr bool same(core::SculptMode core_mode, sim::SculptModeId session_mode) {
  return static_cast<int>(core_mode) == static_cast<int>(session_mode);
}
constexpr bool same(BallBrush brush, sim::SculptModeId session_mode) {
  return sim::kFirstBallBrushMode + static_cast<int>(brush) == static_cast<int>(session_mode);
}
}  // namespace codec_detail

static_assert(codec_detail::same(core::SculptMode::kAdd, sim::SculptModeId::kAdd));
static_assert(codec_detail::same(core::SculptMode::kSubtract, sim::SculptModeId::kSubtract));
static_assert(codec_detail::same(core::SculptMode::kUnion, sim::SculptModeId::kUnion));
static_assert(codec_detail::same(core::SculptMode::kDifference, sim::SculptModeId::kDifference));
static_assert(codec_detail::same(core::SculptMode::kSmooth, sim::SculptModeId::kSmooth));
static_assert(codec_detail::same(BallBrush::kClay, sim::SculptModeId::kClay));
static_assert(codec_detail::same(BallBrush::kFlatten, sim::SculptModeId::kFlatten));
static_assert(codec_detail::same(BallBrush::kInflate, sim::SculptModeId::kInflate));
static_assert(codec_detail::same(BallBrush::kPinch, sim::SculptModeId::kPinch));
static_assert(codec_detail::same(BallBrush::kGrab, sim::SculptModeId::kGrab));
// core's last mode is the last before the format's brushes, and the last
// brush the format's last mode: a mode added to core, or a brush to the
// station, must be added to the format too.
static_assert(static_cast<int>(core::SculptMode::kSmooth) + 1 == sim::kFirstBallBrushMode);
static_assert(sim::kFirstBallBrushMode + kBallBrushCount == sim::kSculptModeCount);
static_assert(static_cast<int>(sim::ToolShape::kCone) + 1 == sim::kToolShapeCount);

/// A session mode below kFirstBallBrushMode (asserted) as core's.
constexpr core::SculptMode to_core(sim::SculptModeId mode) {
  return static_cast<core::SculptMode>(mode);  // same order, checked above
}
constexpr sim::SculptModeId to_session(core::SculptMode mode) {
  return static_cast<sim::SculptModeId>(mode);
}

/// A command's choice byte as a mode, a ball brush or a tool shape; nothing
/// when it names none of that kind (the session readers refuse a choice
/// that names nothing before it gets here).
constexpr std::optional<core::SculptMode> sculpt_mode_of_choice(uint8_t choice) {
  if (choice >= sim::kFirstBallBrushMode) return std::nullopt;
  return static_cast<core::SculptMode>(choice);
}
constexpr std::optional<BallBrush> ball_brush_of_choice(uint8_t choice) {
  if (choice < sim::kFirstBallBrushMode || choice >= sim::kSculptModeCount) return std::nullopt;
  return static_cast<BallBrush>(choice - sim::kFirstBallBrushMode);
}
constexpr std::optional<sim::ToolShape> tool_shape_of_choice(uint8_t choice) {
  if (choice >= sim::kToolShapeCount) return std::nullopt;
  return static_cast<sim::ToolShape>(choice);
}

constexpr uint8_t choice_of(core::SculptMode mode) {
  return static_cast<uint8_t>(mode);
}
constexpr uint8_t choice_of(BallBrush brush) {
  return static_cast<uint8_t>(sim::kFirstBallBrushMode + static_cast<int>(brush));
}
constexpr uint8_t choice_of(sim::ToolShape shape) {
  return static_cast<uint8_t>(shape);
}
/// The mode command's choice for what `settings` sculpt with: the brush if
/// one is chosen, else the mode.
constexpr uint8_t mode_choice_of(const StationSettings& settings) {
  return settings.brush ? choice_of(*settings.brush) : choice_of(settings.mode);
}

/// A tool as a session carries it (kToolVoxels) and back; exact both ways
/// (the session's readers check a ToolVoxels before it gets here, so the
/// second asserts nothing). `tool`'s sides must be at most
/// sim::kMaxToolVoxelsEdge (asserted).
sim::ToolVoxels tool_voxels_of(const core::Tool& tool);
core::Tool tool_of(const sim::ToolVoxels& voxels);

}  // namespace sculpt::station
