#include "sculpt/station/app/station_loop.h"

#include <algorithm>

namespace sculpt::station {
namespace {

constexpr float kMinSize = 0.5f;

}  // namespace

core::Tool make_tool(sim::ToolShape shape, float a, float b) {
  a = std::max(a, kMinSize);
  b = std::max(b, kMinSize);
  switch (shape) {
    case sim::ToolShape::kSphere:
      return core::make_sphere_tool(a);
    case sim::ToolShape::kCube:
      return core::make_cube_tool(a);
    case sim::ToolShape::kCylinder:
      return core::make_cylinder_tool(a, b);
    case sim::ToolShape::kRing:
      return core::make_ring_tool(a, b);
    case sim::ToolShape::kCone:
      return core::make_cone_tool(a, b);
  }
  return core::make_sphere_tool(a);
}

float tool_size_vox(sim::ToolShape shape, float a, float b) {
  a = std::max(a, kMinSize);
  b = std::max(b, kMinSize);
  switch (shape) {
    case sim::ToolShape::kSphere:
      return 2 * a;
    case sim::ToolShape::kCube:
      return a;
    case sim::ToolShape::kCylinder:
    case sim::ToolShape::kCone:
      return std::max(2 * a, b);
    case sim::ToolShape::kRing:
      return 2 * (a + b);
  }
  return 2 * a;
}

StationLoop::StationLoop(const Options& options)
    : options_(options),
      integrator_(options.pose),
      sampler_(tool_size_vox(settings_.shape, settings_.size_a_vox, settings_.size_b_vox),
               settings_.spacing) {
  new_volume(options.volume_dims, options.volume_fill);
  hal::ToolPose start;
  start.position = glm::vec3(options.volume_dims) * 0.5f;
  integrator_.reset(start);
}

void StationLoop::new_volume(glm::ivec3 dims, uint8_t fill) {
  if (pressed_) release();
  sculptor_.reset();
  volume_ = std::make_unique<core::Volume>(dims, fill);
  sculptor_ = std::make_unique<core::Sculptor>(*volume_);
  apply_tool();
  sculptor_->set_mirror(settings_.mirror);
  mesh_ = core::MeshCache(0);
}

void StationLoop::apply_tool() {
  sculptor_->set_tool(make_tool(settings_.shape, settings_.size_a_vox, settings_.size_b_vox));
  reset_sampler();
}

void StationLoop::reset_sampler() {
  sampler_ =
      hal::StrokeSampler(tool_size_vox(settings_.shape, settings_.size_a_vox, settings_.size_b_vox),
                         settings_.spacing);
}

void StationLoop::handle(const sim::Command& c) {
  using K = sim::CommandKind;
  switch (c.kind) {
    case K::kPress:
      press();
      break;
    case K::kRelease:
      release();
      break;
    case K::kTool:
      // A tool change ends the stroke: the dabs of one stroke share one tool.
      if (pressed_) release();
      settings_.shape = static_cast<sim::ToolShape>(c.choice);
      settings_.size_a_vox = c.values[0];
      settings_.size_b_vox = c.values[1];
      apply_tool();
      break;
    case K::kMode:
      settings_.mode = static_cast<core::SculptMode>(c.choice);
      break;
    case K::kStrength:
      settings_.strength = std::clamp(c.values[0], 0.0f, 1.0f);
      break;
    case K::kSpacing:
      if (pressed_) release();
      settings_.spacing = std::max(c.values[0], 0.01f);
      reset_sampler();  // the tool itself is unchanged
      break;
    case K::kMirror:
      if (c.choice == sim::kMirrorOff) {
        settings_.mirror.reset();
      } else {
        settings_.mirror = core::MirrorPlane{c.choice, c.values[0]};
      }
      sculptor_->set_mirror(settings_.mirror);
      break;
    case K::kUndo:
      if (pressed_) release();
      counters_.undos += sculptor_->undo() ? 1 : 0;
      break;
    case K::kRedo:
      if (pressed_) release();
      counters_.redos += sculptor_->redo() ? 1 : 0;
      break;
    case K::kVolume: {
      const glm::ivec3 dims(static_cast<int>(c.values[0]), static_cast<int>(c.values[1]),
                            static_cast<int>(c.values[2]));
      if (core::Volume::validate(dims, {}).ok()) {
        new_volume(dims, static_cast<uint8_t>(std::clamp(c.values[3], 0.0f, 255.0f)));
      }
      break;
    }
    case K::kToolPose: {
      if (pressed_) release();
      hal::ToolPose p;
      p.position = glm::vec3(c.values[0], c.values[1], c.values[2]);
      p.orientation = glm::normalize(glm::quat(c.values[3], c.values[4], c.values[5], c.values[6]));
      integrator_.reset(p);
      break;
    }
  }
}

void StationLoop::press() {
  if (pressed_) return;
  pressed_ = true;
  ++counters_.strokes;
  sculptor_->begin_stroke();
  dabs_.clear();
  sampler_.begin(integrator_.pose(), dabs_);
  sculpt(dabs_);
}

void StationLoop::release() {
  if (!pressed_) return;
  pressed_ = false;
  sampler_.end();
  sculptor_->end_stroke();
}

void StationLoop::sculpt(const std::vector<hal::Dab>& dabs) {
  for (const hal::Dab& d : dabs) {
    core::Dab dab;
    dab.position_vox = d.position;
    dab.orientation = d.orientation;
    dab.mode = settings_.mode;
    dab.strength = settings_.strength;
    sculptor_->dab(dab);
    ++counters_.dabs;
  }
}

void StationLoop::handle(const hal::InputEvent& e) {
  switch (e.kind) {
    case hal::InputKind::kMotion: {
      ++counters_.motion_samples;
      const hal::ToolPose& pose = integrator_.update(e);
      if (pressed_) {
        dabs_.clear();
        sampler_.add(pose, dabs_);
        sculpt(dabs_);
      }
      break;
    }
    case hal::InputKind::kButton:
      if (e.button == 0) {
        e.pressed ? press() : release();
      } else if (e.button == 1 && e.pressed) {
        settings_.mode = settings_.mode == core::SculptMode::kAdd ? core::SculptMode::kSubtract
                                                                  : core::SculptMode::kAdd;
      }
      break;
    case hal::InputKind::kDisconnected:
      ++counters_.disconnects;
      release();
      break;
    case hal::InputKind::kConnected:
    case hal::InputKind::kBattery:
      break;
  }
}

int64_t StationLoop::update_mesh() {
  if (!options_.mesh) return 0;
  return mesh_.update(*volume_).bricks_meshed;
}

}  // namespace sculpt::station
