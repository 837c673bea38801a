#include "sculpt/sim/synth/bundled_sessions.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include <glm/gtc/quaternion.hpp>

#include "sculpt/sim/synth/session_script.h"

namespace sculpt::sim {
namespace {

constexpr float kPi = 3.14159265358979f;
const glm::vec3 kX(1, 0, 0), kY(0, 1, 0), kZ(0, 0, 1);

}  // namespace

Session short_session() {
  SessionScript s(scripted_device(0x046d, 0xc626), scripted_normalizer(), 125);
  s.volume(glm::ivec3(64), 0);
  s.tool(ToolShape::kSphere, 4);
  s.mode(SculptModeId::kAdd);
  s.place(glm::vec3(16, 32, 32));
  s.rest(0.1f);
  s.press();
  s.follow(line_path(glm::vec3(16, 32, 32), glm::vec3(48, 32, 32)), 0.5f);
  s.release();
  s.tool(ToolShape::kCube, 6);
  s.move_to(glm::vec3(32, 20, 32), 0.3f);
  s.press();
  s.follow(arc_path(glm::vec3(32, 32, 32), kX, kY, 12, -kPi / 2, kPi / 2), 0.6f,
           [](float t) { return glm::angleAxis(t * kPi / 2, glm::vec3(0, 0, 1)); });
  s.release();
  s.mode(SculptModeId::kSubtract);
  s.strength(0.7f);
  s.tool(ToolShape::kSphere, 3);
  s.move_to(glm::vec3(16, 32, 36), 0.3f);
  s.press();
  s.follow(zigzag_path(glm::vec3(16, 32, 36), kX, kY, 32, 6, 3), 0.6f);
  s.release();
  s.undo();
  s.redo();
  // The device is pulled out mid-stroke: the stroke must end cleanly, and
  // the re-plugged device carries on.
  s.move_to(glm::vec3(40, 40, 30), 0.2f);
  s.press();
  s.follow(line_path(glm::vec3(40, 40, 30), glm::vec3(40, 48, 30)), 0.2f);
  s.unplug_and_replug(0.5f);
  s.rest(0.1f);
  s.press();
  s.follow(line_path(s.pose().position, s.pose().position + glm::vec3(-8, 0, 0)), 0.2f);
  s.release();
  return s.finish();
}

Session demo_session() {
  SessionScript s(scripted_device(0x256f, 0xc635), scripted_normalizer(), 250);
  const glm::vec3 c(128, 128, 118);  // head centre; the face looks along +z
  s.volume(glm::ivec3(256), 0);

  // The head: a big ball dragged upward into an egg.
  s.tool(ToolShape::kSphere, 66);
  s.mode(SculptModeId::kAdd);
  s.spacing(0.1f);  // dabs 13 voxels apart: a smooth egg, not two balls
  s.place(c - glm::vec3(0, 12, 0));
  s.rest(0.05f);
  s.press();
  s.follow(line_path(c - glm::vec3(0, 12, 0), c + glm::vec3(0, 24, 0)), 0.4f);
  s.release();
  s.spacing(0.25f);
  const glm::vec3 crown_centre = c + glm::vec3(0, 24, 0);  // centre of the egg's upper ball

  // Eye sockets, mirrored across x = 128: one stroke carves both.
  s.mirror(0, 128);
  s.tool(ToolShape::kSphere, 13);
  s.mode(SculptModeId::kSubtract);
  const glm::vec3 eye = c + glm::vec3(-26, 18, 56);
  s.move_to(eye, 0.6f);
  s.press();
  s.follow(line_path(eye, eye + glm::vec3(-4, 0, 2)), 0.2f);
  s.release();
  // Eyeballs.
  s.tool(ToolShape::kSphere, 8);
  s.mode(SculptModeId::kAdd);
  s.move_to(eye + glm::vec3(-2, 0, -3), 0.3f);
  s.press();
  s.rest(0.05f);
  s.release();
  // Ears: ring tools turned to face sideways, mirrored.
  s.tool(ToolShape::kRing, 12, 5);
  const glm::quat sideways = glm::angleAxis(kPi / 2, kY);
  const glm::vec3 ear = c + glm::vec3(-64, 6, 0);
  s.follow(line_path(s.pose().position, ear), 0.8f,
           [&](float t) { return glm::slerp(glm::quat(1, 0, 0, 0), sideways, t); });
  s.press();
  s.follow(line_path(ear, ear + glm::vec3(0, -10, 0)), 0.3f);
  s.release();
  s.mirror(-1, 0);

  // A stray cut across the cheek, undone.
  s.tool(ToolShape::kCube, 10);
  s.mode(SculptModeId::kSubtract);
  s.follow(line_path(s.pose().position, c + glm::vec3(30, -20, 58)), 0.6f,
           [&](float t) { return glm::slerp(sideways, glm::quat(1, 0, 0, 0), t); });
  s.press();
  s.follow(line_path(c + glm::vec3(30, -20, 58), c + glm::vec3(40, -30, 50)), 0.2f);
  s.release();
  s.undo();

  // The nose: a ridge of small balls running down and out of the face.
  s.tool(ToolShape::kSphere, 7);
  s.mode(SculptModeId::kAdd);
  const glm::vec3 bridge = c + glm::vec3(0, 12, 62);
  s.move_to(bridge, 0.5f);
  s.press();
  s.follow(line_path(bridge, c + glm::vec3(0, -8, 74)), 0.5f);
  s.release();
  // Smooth the ridge.
  s.mode(SculptModeId::kSmooth);
  s.tool(ToolShape::kSphere, 9);
  s.press();
  s.follow(line_path(c + glm::vec3(0, -8, 72), bridge), 0.4f);
  s.release();

  // The mouth: a smile carved along an arc.
  s.mode(SculptModeId::kSubtract);
  s.tool(ToolShape::kSphere, 5);
  const glm::vec3 mouth_centre = c + glm::vec3(0, -4, 58);
  const auto smile = arc_path(mouth_centre, kX, kY, 24, kPi * 1.2f, kPi * 1.8f);
  s.move_to(smile(0), 0.5f);
  s.press();
  s.follow(smile, 0.8f);
  s.release();

  // A spiral on the crown and a curl of hair made by a helix.
  s.tool(ToolShape::kSphere, 4);
  s.mode(SculptModeId::kAdd);
  // The spiral lies on the crown: a flat spiral projected onto the egg.
  const auto flat = spiral_path(crown_centre, kX, kZ, 2, 34, 2.5f);
  const Path spiral = [&, flat](float t) {
    const glm::vec3 p = flat(t);
    const float r2 = glm::dot(p - crown_centre, p - crown_centre);
    return p + kY * (std::sqrt(std::max(0.0f, 67.0f * 67.0f - r2)) + 0.0f);
  };
  s.move_to(spiral(0), 0.5f);
  s.press();
  s.follow(spiral, 1.5f);
  s.release();
  s.tool(ToolShape::kSphere, 3);
  const auto curl = helix_path(crown_centre + glm::vec3(40, 34, 20), kY, 8, 3, 24);
  s.move_to(curl(0), 0.4f);
  s.press();
  s.follow(curl, 1.2f);
  s.release();
  s.rest(0.2f);
  return s.finish();
}

Session sheet_session() {
  SessionScript s(scripted_device(0x256f, 0xc635), scripted_normalizer(), 250);
  s.volume(glm::ivec3(96), 0);
  auto sheet = [&](SheetAction action, std::initializer_list<float> values) {
    Command c{CommandKind::kSheet, static_cast<uint8_t>(action), {}};
    std::copy(values.begin(), values.end(), c.values);
    s.command(c);
  };
  // A flat 8 x 8 bicubic sheet, 56 voxels square, facing +z.
  const glm::vec3 centre(48, 48, 36);
  sheet(SheetAction::kPlace, {centre.x, centre.y, centre.z, 56, 8, 2});
  sheet(SheetAction::kEdit, {1, 1, 2.5f});  // gaussian, 2.5 control points
  // Pull its middle up along an arc, then push a corner down.
  s.place(centre);
  s.rest(0.1f);
  s.press();
  s.follow(arc_path(centre + glm::vec3(-14, 0, 0), kX, kZ, 14, 0, kPi / 2), 1.0f);
  s.release();
  s.move_to(centre + glm::vec3(14, 14, 0), 0.4f);
  s.press();
  s.follow(line_path(s.pose().position, s.pose().position + glm::vec3(0, 0, -10)), 0.5f);
  s.release();
  // Its shell into the material, the sheet put away, and a groove cut across.
  sheet(SheetAction::kAdd, {4});
  sheet(SheetAction::kRemove, {});
  s.tool(ToolShape::kSphere, 2.5f);
  s.spacing(0.15f);
  s.mode(SculptModeId::kSubtract);
  s.move_to(glm::vec3(22, 28, 36), 0.4f);
  s.press();
  s.follow(zigzag_path(glm::vec3(22, 28, 36), kX, kY, 52, 6, 3), 1.2f);
  s.release();
  s.rest(0.2f);
  return s.finish();
}

// A bust in a 512^3 block: the station's workload at eight times the
// demo's voxels, with big tools (a 110-voxel ball for the head, 70 for the
// shoulders) and fine ones (eyes, brow, lips, hair), mirrored.
Session bust_session() {
  SessionScript s(scripted_device(0x256f, 0xc635), scripted_normalizer(), 250);
  const glm::vec3 c(256, 300, 250);  // head centre; the face looks along +z
  s.volume(glm::ivec3(512), 0);

  // Shoulders: a wide ball swept across, low down.
  s.tool(ToolShape::kSphere, 70);
  s.mode(SculptModeId::kAdd);
  s.spacing(0.1f);
  const glm::vec3 chest = c - glm::vec3(0, 170, 10);
  s.place(chest - glm::vec3(110, 0, 0));
  s.rest(0.05f);
  s.press();
  s.follow(line_path(chest - glm::vec3(110, 0, 0), chest + glm::vec3(110, 0, 0)), 0.6f);
  s.release();
  // The neck, then the head: a big ball dragged upward into an egg.
  s.tool(ToolShape::kSphere, 45);
  s.move_to(chest + glm::vec3(0, 40, 0), 0.3f);
  s.press();
  s.follow(line_path(chest + glm::vec3(0, 40, 0), c - glm::vec3(0, 60, 0)), 0.4f);
  s.release();
  s.tool(ToolShape::kSphere, 110);
  s.move_to(c - glm::vec3(0, 10, 0), 0.3f);
  s.press();
  s.follow(line_path(c - glm::vec3(0, 10, 0), c + glm::vec3(0, 30, 0)), 0.4f);
  s.release();
  s.spacing(0.25f);

  // Eye sockets and eyeballs, mirrored across x = 256.
  s.mirror(0, 256);
  s.tool(ToolShape::kSphere, 24);
  s.mode(SculptModeId::kSubtract);
  const glm::vec3 eye = c + glm::vec3(-44, 24, 96);
  s.move_to(eye, 0.5f);
  s.press();
  s.follow(line_path(eye, eye + glm::vec3(-6, 0, 3)), 0.2f);
  s.release();
  s.tool(ToolShape::kSphere, 14);
  s.mode(SculptModeId::kAdd);
  s.move_to(eye + glm::vec3(-3, 0, -6), 0.3f);
  s.press();
  s.rest(0.05f);
  s.release();
  // The brow: a ridge of small balls over each eye.
  s.tool(ToolShape::kSphere, 8);
  s.move_to(eye + glm::vec3(22, 30, -6), 0.3f);
  s.press();
  s.follow(arc_path(eye + glm::vec3(0, 8, -6), kX, kY, 28, kPi * 0.2f, kPi * 0.8f), 0.5f);
  s.release();
  s.mirror(-1, 0);

  // The nose, smoothed; the lips carved and built.
  s.tool(ToolShape::kSphere, 12);
  const glm::vec3 bridge = c + glm::vec3(0, 16, 106);
  s.move_to(bridge, 0.4f);
  s.press();
  s.follow(line_path(bridge, c + glm::vec3(0, -20, 124)), 0.5f);
  s.release();
  s.mode(SculptModeId::kSmooth);
  s.tool(ToolShape::kSphere, 16);
  s.press();
  s.follow(line_path(c + glm::vec3(0, -20, 120), bridge), 0.4f);
  s.release();
  s.mode(SculptModeId::kSubtract);
  s.tool(ToolShape::kSphere, 6);
  const glm::vec3 mouth = c + glm::vec3(0, -12, 96);
  const auto lips = arc_path(mouth, kX, kY, 36, kPi * 1.25f, kPi * 1.75f);
  s.move_to(lips(0), 0.4f);
  s.press();
  s.follow(lips, 0.6f);
  s.release();

  // Hair: a zigzag of small balls laid on the crown, and a cut undone.
  s.mode(SculptModeId::kAdd);
  s.tool(ToolShape::kSphere, 7);
  const glm::vec3 crown_centre = c + glm::vec3(0, 30, 0);  // the head ball's upper centre
  const auto flat = zigzag_path(crown_centre + glm::vec3(-60, 0, -30), kX, kZ, 120, 50, 4);
  const Path hair = [=](float t) {
    const glm::vec3 p = flat(t);
    const glm::vec2 d(p.x - crown_centre.x, p.z - crown_centre.z);
    return glm::vec3(
        p.x, crown_centre.y + std::sqrt(std::max(0.0f, 112.0f * 112.0f - glm::dot(d, d))), p.z);
  };
  s.move_to(hair(0), 0.4f);
  s.press();
  s.follow(hair, 1.2f);
  s.release();
  s.tool(ToolShape::kCube, 30);
  s.mode(SculptModeId::kSubtract);
  s.move_to(c + glm::vec3(60, -40, 90), 0.3f);
  s.press();
  s.follow(line_path(c + glm::vec3(60, -40, 90), c + glm::vec3(80, -60, 70)), 0.2f);
  s.release();
  s.undo();
  s.rest(0.2f);
  return s.finish();
}

std::vector<std::string_view> bundled_session_names() {
  return {"short", "demo", "sheet", "bust"};
}

Session bundled_session(std::string_view name) {
  if (name == "short") return short_session();
  if (name == "demo") return demo_session();
  if (name == "sheet") return sheet_session();
  if (name == "bust") return bust_session();
  return {};
}

std::string bundled_session_path(std::string_view name) {
  return std::string(SCULPT_SESSIONS_DIR) + "/" + std::string(name) + ".scs";
}

}  // namespace sculpt::sim
