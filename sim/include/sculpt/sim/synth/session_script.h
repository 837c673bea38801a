#pragma once
// Scripted sessions: a script says where the tool should go ("follow this
// helix for 3 s", "press", "switch to the ring tool") and the script emits the
// raw reports a SpaceMouse would send to make it so.
//
// The script steers in closed loop through the real pipeline: each report it
// emits goes through the same parser, normaliser, deflection integral and
// pose integrator the station runs, and the next report's deflection is chosen
// from the pose actually reached. So the recorded bytes reproduce the intended
// path under the session's own normaliser settings, and a replay of the
// session follows it.

#include <functional>
#include <memory>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "sculpt/hal/input/motion_pipeline.h"
#include "sculpt/hal/normalizer/normalizer_config.h"
#include "sculpt/hal/pose/pose_integrator.h"
#include "sculpt/hal/types/quirks.h"
#include "sculpt/sim/session/session.h"

namespace sculpt::sim {

/// A device description for a 3Dconnexion device of the quirks table.
hal::DeviceInfo scripted_device(uint16_t vendor_id, uint16_t product_id);
/// Normaliser settings for scripted sessions: linear, no deadzone, no filter,
/// so a deflection means exactly what the script asked for.
hal::NormalizerConfig scripted_normalizer();

/// A path in voxel units, for s from 0 to 1.
using Path = std::function<glm::vec3(float s)>;
/// Orientation along a path, for s from 0 to 1.
using Turn = std::function<glm::quat(float s)>;

class SessionScript {
 public:
  /// Reports at `report_hz` (3D mice send 60 to 1000 per second).
  SessionScript(hal::DeviceInfo device, hal::NormalizerConfig normalizer, int report_hz = 250,
                hal::PoseIntegratorConfig pose = {});
  ~SessionScript();

  // Station commands, recorded at the current time.
  void volume(glm::ivec3 size, uint8_t fill);
  void tool(ToolShape shape, float size_a_vox, float size_b_vox = 0.0f);
  void mode(SculptModeId mode);
  void strength(float strength);
  void spacing(float fraction);
  void mirror(int axis, float at_vox);  ///< axis -1: off
  void undo();
  void redo();
  /// Any station command (the NURBS sheet's, for instance).
  void command(const Command& c);
  /// Places the tool (a tool_pose command); the pose integration restarts there.
  void place(glm::vec3 position_vox, glm::quat orientation = glm::quat(1, 0, 0, 0));

  /// Device button 0 goes down / up (a button report): the tool presses / lifts.
  void press();
  void release();
  /// Steers the tool along `path` (which should start where the tool is) in
  /// `seconds`, turning it along `turn` when given.
  void follow(const Path& path, float seconds, const Turn& turn = {});
  /// Straight to `target`.
  void move_to(glm::vec3 target_vox, float seconds);
  /// The cap is released: one report at rest, then silence for `seconds`.
  void rest(float seconds);
  /// The device is unplugged (a removal event), and plugged back `seconds` later.
  void unplug_and_replug(float seconds);

  /// The pose the pipeline has reached.
  const hal::ToolPose& pose() const;
  int64_t now_ns() const { return t_ns_; }
  /// The session so far.
  const Session& session() const { return session_; }
  Session finish() { return std::move(session_); }

 private:
  void emit(std::span<const uint8_t> report);
  void emit_motion(const std::array<float, 6>& axes);
  void emit_buttons(uint32_t mask);
  void tick() { t_ns_ += period_ns_; }
  // The id the script's one device reports under, as a replay gives it.
  static constexpr uint32_t kDeviceId = 0;
  // The device's parser and the normaliser, as a replay makes them.
  std::unique_ptr<hal::MotionPipeline> fresh_pipeline() const;

  Session session_;
  const hal::DeviceQuirks* quirks_;
  hal::NormalizerConfig normalizer_;
  std::unique_ptr<hal::MotionPipeline> pipeline_;
  hal::PoseIntegrator integrator_;
  hal::PoseIntegratorConfig pose_config_;
  int64_t period_ns_;
  int64_t t_ns_ = 1'000'000'000;
  std::array<float, 6> last_axes_{};
  std::vector<hal::InputEvent> scratch_;
};

/// Paths the generators of the issue name; all in voxel units.
Path line_path(glm::vec3 from, glm::vec3 to);
/// Arc in the plane spanned by unit vectors u, v around `centre`, angles in radians.
Path arc_path(glm::vec3 centre, glm::vec3 u, glm::vec3 v, float radius, float from_angle,
              float to_angle);
/// Helix around the axis through `centre` along unit `axis`, `turns` turns rising `rise` in total.
Path helix_path(glm::vec3 centre, glm::vec3 axis, float radius, float turns, float rise);
/// Archimedean spiral in the plane (u, v) from radius r0 to r1 over `turns` turns.
Path spiral_path(glm::vec3 centre, glm::vec3 u, glm::vec3 v, float r0, float r1, float turns);
/// Zig-zag from `from` along `direction` (length `length`) with `teeth` teeth of amplitude
/// `amplitude` along `across`.
Path zigzag_path(glm::vec3 from, glm::vec3 direction, glm::vec3 across, float length,
                 float amplitude, int teeth);

}  // namespace sculpt::sim
