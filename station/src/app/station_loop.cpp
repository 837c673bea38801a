#include "sculpt/station/app/station_loop.h"

#include "app/morphology_job.h"

#include <glm/geometric.hpp>

#include "sculpt/base/thread_times.h"
#include "sculpt/core/distance/hypertexture.h"
#include "sculpt/core/sculpt/clay_brush.h"
#include "sculpt/core/sculpt/flatten_brush.h"
#include "sculpt/core/sculpt/grab_brush.h"
#include "sculpt/core/sculpt/inflate_brush.h"
#include "sculpt/core/sculpt/pinch_brush.h"
#include "sculpt/core/sculpt/smooth_brush.h"
#include "sculpt/core/shapes/analytic_shapes.h"
#include "sculpt/core/tool/tool_scale.h"
#include "sculpt/hal/types/clock.h"
#include "sculpt/sim/session/command_limits.h"
#include "sculpt/station/settings/command_codec.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace sculpt::station {
namespace {

constexpr float kMinSize = 0.5f;

}  // namespace

core::Tool make_tool(sim::ToolShape shape, float a, float b, float hardness) {
  hardness = std::clamp(hardness, 0.0f, 1.0f);
  a = std::max(a, kMinSize);
  b = std::max(b, kMinSize);
  switch (shape) {
    case sim::ToolShape::kSphere:
      return core::make_sphere_tool(a, hardness);
    case sim::ToolShape::kCube:
      return core::make_cube_tool(a, hardness);
    case sim::ToolShape::kCylinder:
      return core::make_cylinder_tool(a, b, hardness);
    case sim::ToolShape::kRing:
      return core::make_ring_tool(a, b, hardness);
    case sim::ToolShape::kCone:
      return core::make_cone_tool(a, b, hardness);
  }
  return core::make_sphere_tool(a, hardness);
}

core::Volume clay_block(glm::ivec3 dims, int margin) {
  const glm::vec3 lo(static_cast<float>(margin));
  const glm::vec3 hi = glm::vec3(dims) - 1.0f - static_cast<float>(margin);
  if (glm::any(glm::greaterThan(lo, hi))) return core::Volume(dims, 0);
  return core::Volume::from_bricks(dims, {}, [&](const core::Box& box, std::span<uint8_t> out) {
    size_t i = 0;
    for (int z = box.lo.z; z < box.hi.z; ++z)
      for (int y = box.lo.y; y < box.hi.y; ++y)
        for (int x = box.lo.x; x < box.hi.x; ++x, ++i) {
          // Signed distance to the slab's faces (the box's inside is negative).
          const glm::vec3 p(x, y, z);
          const glm::vec3 q = glm::max(lo - p, p - hi);
          const float outside = glm::length(glm::max(q, glm::vec3(0.0f)));
          const float inside = std::min(std::max({q.x, q.y, q.z}), 0.0f);
          out[i] = core::density_from_distance(outside + inside);
        }
  });
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

PathBrush path_brush_of(BallBrush brush) {
  switch (brush) {
    case BallBrush::kClay:
      return PathBrush::kClay;
    case BallBrush::kFlatten:
      return PathBrush::kFlatten;
    case BallBrush::kInflate:
      return PathBrush::kInflate;
    case BallBrush::kPinch:
      return PathBrush::kPinch;
    case BallBrush::kGrab:
      return PathBrush::kGrab;
  }
  return PathBrush::kClay;
}

namespace {

// Every option in range, so the core's asserts hold whatever a session says.
float brush_radius(float radius_vox) {
  return std::clamp(radius_vox, kMinSize, core::kMaxBrushRadiusVox);
}

std::vector<core::StrokeSample> mirrored_path(std::span<const core::StrokeSample> path,
                                              const core::MirrorPlane& mirror) {
  std::vector<core::StrokeSample> out(path.begin(), path.end());
  for (core::StrokeSample& s : out)
    s.position_vox[mirror.axis] = 2.0f * mirror.centre_vox - s.position_vox[mirror.axis];
  return out;
}

}  // namespace

namespace {

// A core ball brush's options for the station's tool size, hardness and
// strength (clamped).
template <class Options>
Options ball_brush_options(float radius_vox, float hardness, float strength) {
  Options o;
  o.radius_vox = brush_radius(radius_vox);
  o.hardness = std::clamp(hardness, 0.0f, 1.0f);
  o.strength = std::clamp(strength, 0.0f, 1.0f);
  return o;
}

}  // namespace

core::Box path_brush_reach(const core::Volume& volume, std::span<const core::StrokeSample> path,
                           float radius_vox, std::optional<core::MirrorPlane> mirror) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  auto cover = [&](std::span<const core::StrokeSample> p) {
    for (const core::StrokeSample& s : p) {
      lo = glm::min(lo, s.position_vox);
      hi = glm::max(hi, s.position_vox);
    }
  };
  cover(path);
  if (mirror) cover(mirrored_path(path, *mirror));
  // A brush writes within its ball's reach, radius + 1, of its path.
  const float reach = brush_radius(radius_vox) + 2.0f;
  const core::Box box{glm::ivec3(glm::floor(lo - reach)), glm::ivec3(glm::ceil(hi + reach)) + 1};
  return core::intersect(box, core::Box{glm::ivec3(0), volume.dims()});
}

int64_t path_brush_stroke(core::Volume& volume, core::Sculptor& sculptor, PathBrush brush,
                          std::span<const core::StrokeSample> path, float radius_vox,
                          float hardness, float strength, std::optional<core::MirrorPlane> mirror) {
  auto with = [&]<class Options>(Options) {
    return ball_brush_options<Options>(radius_vox, hardness, strength);
  };
  auto apply = [&](core::Sculptor& s, std::span<const core::StrokeSample> p) -> int64_t {
    switch (brush) {
      case PathBrush::kSmooth:
        return core::smooth_stroke(volume, s, p, with(core::SmoothBrushOptions{}));
      case PathBrush::kClay:
        return core::clay_stroke(volume, s, p, with(core::ClayBrushOptions{}));
      case PathBrush::kFlatten:
        return core::flatten_stroke(volume, s, p, with(core::FlattenBrushOptions{}));
      case PathBrush::kInflate:
        return core::inflate_stroke(volume, s, p, with(core::InflateBrushOptions{}));
      case PathBrush::kPinch:
        return core::pinch_stroke(volume, s, p, with(core::PinchBrushOptions{}));
      case PathBrush::kGrab:
        return core::grab_stroke(volume, s, p, with(core::GrabBrushOptions{}));
    }
    return 0;
  };
  if (!mirror) return apply(sculptor, path);

  // The core brushes know no mirror, and each is an undo step of its own.
  // For one step, the sculptor records every brick either pass may write
  // and the passes run on a scratch sculptor of the same volume, whose own
  // history is dropped.
  const core::Box box = path_brush_reach(volume, path, radius_vox, mirror);
  if (box.empty()) return 0;
  const std::vector<core::StrokeSample> mirrored = mirrored_path(path, *mirror);
  int64_t changed = 0;
  core::Sculptor scratch(volume);
  sculptor.external_edit(box, [&] { changed = apply(scratch, path) + apply(scratch, mirrored); });
  return changed;
}

namespace {

// The sampler for the default settings: sampler_ is built before settings_
// (their order in the class), so it cannot read them.
hal::StrokeSampler default_sampler() {
  const StationSettings s;
  return hal::StrokeSampler(tool_size_vox(s.shape, s.size_a_vox, s.size_b_vox), s.spacing);
}

}  // namespace

StationLoop::StationLoop(const Options& options)
    : options_(options), integrator_(options.pose), sampler_(default_sampler()) {
  settings_.tracker = options.pose.tracker;
  new_volume(options.volume_dims, options.volume_fill, options.clay_margin);
  hal::ToolPose start;
  start.position = glm::vec3(options.volume_dims) * 0.5f;
  integrator_.reset(start);
}

void StationLoop::new_volume(glm::ivec3 dims, uint8_t fill, int clay_margin) {
  if (pressed_) release();
  retire_sculptor();
  volume_ = clay_margin > 0 ? std::make_unique<core::Volume>(clay_block(dims, clay_margin))
                            : std::make_unique<core::Volume>(dims, fill);
  ++volume_generation_;
  sculptor_ = std::make_unique<core::Sculptor>(*volume_, sculptor_options());
  apply_tool();
  sculptor_->set_mirror(settings_.mirror);
  mesh_ = core::MeshCache(0);
}

void StationLoop::restore(std::unique_ptr<core::Volume> volume, const StationSettings& settings,
                          std::optional<core::Tool> custom_tool,
                          std::optional<core::nurbs::NurbsSurface> sheet) {
  settle();
  if (pressed_) release();
  retire_sculptor();
  volume_ = std::move(volume);
  ++volume_generation_;
  sculptor_ = std::make_unique<core::Sculptor>(*volume_, sculptor_options());
  settings_ = settings;
  settings_.custom_tool = custom_tool.has_value();
  if (custom_tool) {
    settings_.custom_source =
        settings.custom_region.empty() ? CustomToolSource::kFile : CustomToolSource::kRegion;
    custom_base_ = std::move(*custom_tool);
    scale_custom_tool();
  } else {
    settings_.tool_scale = 1.0f;
  }
  sheet_.reset(std::move(sheet));
  apply_tool();
  sculptor_->set_mirror(settings_.mirror);
  mesh_ = core::MeshCache(0);
}

void StationLoop::retire_sculptor() {
  if (!sculptor_) return;
  retired_cache_stats_ = rotation_cache_stats().retired();
  sculptor_.reset();
}

core::RotatedToolCacheStats StationLoop::rotation_cache_stats() const {
  core::RotatedToolCacheStats sum = retired_cache_stats_;
  if (sculptor_) sum += sculptor_->rotation_cache_stats();
  return sum;
}

core::SculptorOptions StationLoop::sculptor_options() const {
  core::SculptorOptions o;
  o.undo_max_bytes = options_.undo_max_bytes;
  o.hand_over_voxels = options_.hand_over_voxels;
  return o;
}

void StationLoop::apply_tool() {
  // A custom tool (tool_ already holds it) outlives the material it came from.
  if (!settings_.custom_tool) {
    tool_ = std::make_shared<const core::Tool>(
        make_tool(settings_.shape, settings_.size_a_vox, settings_.size_b_vox, settings_.hardness));
  }
  sculptor_->set_tool(*tool_);
  ++tool_version_;
  reset_sampler();
  if (stand_ins_ != nullptr) give_stand_ins_the_tool();
}

void StationLoop::show_stand_ins(DabStandIns* board) {
  stand_ins_ = board;
  if (stand_ins_ != nullptr) give_stand_ins_the_tool();
}

void StationLoop::give_stand_ins_the_tool() {
  // A march still running for an earlier tool is let finish on its own: a
  // future from std::async would wait for it when replaced.
  if (stand_in_tool_.valid()) retired_marches_.push_back(std::move(stand_in_tool_));
  std::erase_if(retired_marches_, [](const std::future<DabStandIns::ToolMesh>& f) {
    return f.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
  });
  // A ball's is a sphere, made at once.
  if (tool_->sphere_radius_vox > 0.0f) {
    stand_ins_->set_tool(DabStandIns::ToolMesh::of(*tool_, tool_version_));
    return;
  }
  // Another tool's is marched from its voxels on a thread of its own (tens
  // of milliseconds for a big one, beside the tool change's own) and handed
  // to the board at the first dab that needs it, which waits for it only if
  // it came sooner: a stand-in is ready to draw when it is published.
  stand_in_tool_ = std::async(std::launch::async, [tool = tool_, version = tool_version_] {
    name_this_thread("stand-in-tool");  // not the sculpting thread's name
    return DabStandIns::ToolMesh::of(*tool, version);
  });
}

void StationLoop::set_custom_tool(core::Tool tool, CustomToolSource source, core::Box region) {
  settings_.custom_tool = true;
  settings_.custom_source = source;
  settings_.custom_region = region;
  settings_.tool_scale = 1.0f;
  custom_base_ = std::move(tool);
  tool_ = std::make_shared<const core::Tool>(custom_base_);
  apply_tool();
}

void StationLoop::scale_custom_tool() {
  // A scale the grid cannot take (a restored project's, checked there too)
  // leaves the tool as made.
  const float f = settings_.tool_scale;
  const glm::ivec3 d = core::scaled_tool_dims(custom_base_.density.dims(), f);
  const bool fits = f >= sim::kMinToolScale && f <= sim::kMaxToolScale &&
                    std::max({d.x, d.y, d.z}) <= kMaxScaledToolEdge;
  if (f == 1.0f || !fits) {
    settings_.tool_scale = 1.0f;
    tool_ = std::make_shared<const core::Tool>(custom_base_);
  } else {
    tool_ = std::make_shared<const core::Tool>(core::scale_tool(custom_base_, f));
  }
}

float StationLoop::tool_size() const {
  if (!settings_.custom_tool)
    return tool_size_vox(settings_.shape, settings_.size_a_vox, settings_.size_b_vox);
  const glm::ivec3 d = tool_->density.dims();
  return static_cast<float>(std::max({d.x, d.y, d.z, 1}));
}

void StationLoop::reset_sampler() {
  sampler_ = hal::StrokeSampler(tool_size(), settings_.spacing);
}

void StationLoop::move_tool(const float* v, bool keep_stroke) {
  if (pressed_ && !keep_stroke) release();
  hal::ToolPose p;
  p.position = glm::vec3(v[0], v[1], v[2]);
  const glm::quat q(v[3], v[4], v[5], v[6]);
  p.orientation = glm::dot(q, q) > 0 ? glm::normalize(q) : glm::quat(1, 0, 0, 0);
  integrator_.reset(p);
  tool_moved();
}

void StationLoop::tool_moved() {
  if (!pressed_) return;
  if (sheet_held_) {
    sheet_.drag(glm::dvec3(integrator_.pose().position));
    return;
  }
  dabs_.clear();
  sampler_.add(integrator_.pose(), dabs_);
  sculpt(dabs_);
}

void StationLoop::touch_moved(const hal::InputEvent& e) {
  const float radius = tool_size() * 0.5f;
  const glm::vec3 device = integrator_.pose().position;
  // How far the device pushes: a 3D mouse's cap, its largest translation
  // axis; a device in position control has no cap, and pushes as far as it
  // has gone past the proxy, a tool's radius counting as full.
  float deflection = 0.0f;
  if (e.absolute) {
    deflection =
        std::min(glm::length(device - touch_.last().proxy_vox) / std::max(radius, 1.0f), 1.0f);
  } else {
    for (int a = hal::kTx; a <= hal::kTz; ++a)
      deflection = std::max(deflection, std::abs(e.axes[static_cast<size_t>(a)]));
  }
  const TouchResult& t = touch_.update(*volume_, volume_generation_, device, deflection, radius);
  // The device point never sinks into the material: it stays on the proxy,
  // so pulling the cap back lifts the tool at once (a rate-controlled point
  // left inside would have to travel back out first). A device in position
  // control sets it afresh with its next sample.
  integrator_.place(t.proxy_vox);
  if (pressed_ && t.contact && !t.pressing_in) {
    // Resting on the material with the button held sculpts nothing: the
    // stroke goes on, the tool held where it last sculpted.
    return;
  }
  integrator_.place(t.tool_vox);
  tool_moved();
  integrator_.place(t.proxy_vox);
}

void StationLoop::handle(const sim::Command& c) {
  settle();
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
      settings_.shape = tool_shape_of_choice(c.choice).value_or(settings_.shape);
      settings_.custom_tool = false;
      settings_.size_a_vox = c.values[0];
      settings_.size_b_vox = c.values[1];
      apply_tool();
      break;
    case K::kMode:
      if (const auto brush = ball_brush_of_choice(c.choice)) {
        settings_.brush = brush;
      } else if (const auto mode = sculpt_mode_of_choice(c.choice)) {
        settings_.mode = *mode;
        settings_.brush.reset();
      }
      break;
    case K::kAccumulate:
      settings_.accumulate = c.choice != 0;
      break;
    case K::kStrength:
      settings_.strength = std::clamp(c.values[0], 0.0f, 1.0f);
      break;
    case K::kHardness:
      // A new tool: as a tool change, it ends the stroke.
      if (pressed_) release();
      settings_.hardness = std::clamp(c.values[0], 0.0f, 1.0f);
      apply_tool();
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
      interrupt_stroke();  // a swept stroke keeps one mirror throughout
      sculptor_->set_mirror(settings_.mirror);
      break;
    case K::kUndo:
      if (pressed_) release();
      counters_.undos += (settings_.sheet_editing ? sheet_.undo() : sculptor_->undo()) ? 1 : 0;
      break;
    case K::kRedo:
      if (pressed_) release();
      counters_.redos += (settings_.sheet_editing ? sheet_.redo() : sculptor_->redo()) ? 1 : 0;
      break;
    case K::kTouch:
      settings_.touch = c.choice != 0;
      touch_.reset();
      break;
    case K::kClutch:
      clutch_key_ = c.choice != 0;
      apply_clutch();
      break;
    case K::kTracker: {
      // command_limits.h keeps the scale in range and the rotation unit.
      const glm::dquat q(c.values[1], c.values[2], c.values[3], c.values[4]);
      settings_.tracker = {.scale_vox_per_mm = c.values[0],
                           .tracker_to_sculpture = glm::normalize(q)};
      integrator_.calibrate_tracker(settings_.tracker);
      break;
    }
    case K::kSheet:
      sheet_command(c);
      break;
    case K::kMorphology:
      morphology(c);
      break;
    case K::kVolume: {
      const glm::ivec3 dims(static_cast<int>(c.values[0]), static_cast<int>(c.values[1]),
                            static_cast<int>(c.values[2]));
      if (core::Volume::validate(dims, {}).ok()) {
        const float v = std::isfinite(c.values[3]) ? c.values[3] : 0.0f;
        if (c.choice == sim::kVolumeClay) {
          new_volume(dims, 0, static_cast<int>(std::clamp(v, 0.0f, 65536.0f)));
        } else {
          new_volume(dims, static_cast<uint8_t>(std::clamp(v, 0.0f, 255.0f)), 0);
        }
      }
      break;
    }
    case K::kToolPose:
      move_tool(c.values, /*keep_stroke=*/false);
      break;
    case K::kPointer:
      move_tool(c.values, /*keep_stroke=*/true);
      break;
    case K::kHypertexture: {
      if (pressed_) release();
      const glm::vec3 centre(c.values[0], c.values[1], c.values[2]);
      const float radius = std::clamp(c.values[3], 1.0f, 128.0f);
      core::HypertextureOptions h;
      h.width_vox = std::clamp(c.values[4], 0.5f, 32.0f);
      h.seed = static_cast<uint32_t>(std::clamp(c.values[5], 0.0f, 1.0e6f));
      h.threads = 1;  // the same result on every machine
      if (!std::isfinite(centre.x) || !std::isfinite(centre.y) || !std::isfinite(centre.z)) break;
      const float reach = radius + h.width_vox;
      core::Box box{glm::ivec3(glm::floor(centre - reach)),
                    glm::ivec3(glm::ceil(centre + reach)) + 1};
      box = core::intersect(box, core::Box{glm::ivec3(0), volume_->dims()});
      if (box.empty()) break;
      sculptor_->external_edit(box, [&] { core::bake_hypertexture(*volume_, box, h); });
      break;
    }
    case K::kToolFromRegion: {
      // Clamped to the block; a region with no voxel in it changes nothing.
      core::Box region;
      for (int a = 0; a < 3; ++a) {
        region.lo[a] = std::clamp(static_cast<int>(std::floor(c.values[a])), 0, volume_->dims()[a]);
        region.hi[a] =
            std::clamp(static_cast<int>(std::ceil(c.values[3 + a])), 0, volume_->dims()[a]);
      }
      if (region.empty()) break;
      if (pressed_) release();
      set_custom_tool(core::tool_from_volume(*volume_, region), CustomToolSource::kRegion, region);
      break;
    }
    case K::kToolVoxels:
      // The readers checked the voxels; a command made in memory may have none.
      if (c.voxels == nullptr) break;
      if (pressed_) release();
      set_custom_tool(tool_of(*c.voxels), CustomToolSource::kFile);
      break;
    case K::kToolScale: {
      // command_limits.h keeps the factor in [0.125, 8]; a grid over the
      // largest tool is refused here as the controller refuses it.
      if (!settings_.custom_tool) break;
      const float f = std::clamp(c.values[0], sim::kMinToolScale, sim::kMaxToolScale);
      const glm::ivec3 d = core::scaled_tool_dims(custom_base_.density.dims(), f);
      if (std::max({d.x, d.y, d.z}) > kMaxScaledToolEdge) break;
      if (pressed_) release();
      settings_.tool_scale = f;
      scale_custom_tool();
      apply_tool();
      break;
    }
  }
}

void StationLoop::press() {
  if (pressed_) return;
  pressed_ = true;
  stand_in_last_.reset();
  sheet_press_ = settings_.sheet_editing;
  if (sheet_press_) {
    const Status grabbed =
        sheet_.grab(glm::dvec3(integrator_.pose().position), settings_.sheet_drag);
    sheet_held_ = grabbed.ok();
    sheet_problem_ = grabbed.ok() ? std::string() : grabbed.error().message();
    ++(sheet_held_ ? counters_.sheet_grabs : counters_.sheet_misses);
    return;
  }
  ++counters_.strokes;
  sculptor_->begin_stroke();
  dabs_.clear();
  // In touch mode, pressing while the tool rests on the material sculpts
  // nothing yet (the push past the threshold does, touch_moved()); pressing
  // while pushing past it starts where the push puts the tool.
  const TouchResult& t = touch_.last();
  const bool touching = settings_.touch && !settings_.sheet_editing && t.contact;
  if (touching && t.pressing_in) integrator_.place(t.tool_vox);
  sampler_.begin(integrator_.pose(), dabs_);
  if (touching) integrator_.place(t.proxy_vox);
  if (touching && !t.pressing_in) return;
  sculpt(dabs_);
}

void StationLoop::release() {
  if (!pressed_) return;
  pressed_ = false;
  stand_in_last_.reset();
  if (sheet_press_) {  // the press went to the sheet, not to a stroke
    if (sheet_held_) sheet_.release();
    sheet_held_ = false;
    sheet_press_ = false;
    return;
  }
  sampler_.end();
  stroke_.reset();  // finishes it
  resume_stroke_ = false;
  sculptor_->end_stroke();
  finish_brush();
}

void StationLoop::interrupt_stroke() {
  if (!stroke_ && brush_path_.empty()) return;
  stroke_.reset();
  if (!brush_path_.empty()) {
    finish_brush();
    // The rest of the press is one undo step again.
    if (pressed_) sculptor_->begin_stroke();
  }
  resume_stroke_ = true;
}

void StationLoop::finish_brush() {
  if (brush_path_.empty()) return;
  preview_.revert(*volume_);
  path_brush_stroke(*volume_, *sculptor_, brush_, brush_path_, tool_size() * 0.5f,
                    settings_.hardness, brush_strength_, brush_mirror_);
  brush_path_.clear();
}

void StationLoop::catch_up_brush_preview(int64_t now_ns) {
  if (!options_.preview_brushes || dabs_not_yet_shown() <= 0) return;
  if (now_ns - preview_ended_ns_ < 2 * preview_took_ns_) return;
  show_brush_preview();
}

void StationLoop::show_brush_preview() {
  const int64_t start_ns = hal::monotonic_ns();
  const float radius = tool_size() * 0.5f;
  const core::Box region = path_brush_reach(*volume_, brush_path_, radius, brush_mirror_);
  if (region.empty()) return;
  // A scratch sculptor: a preview is no undo step (finish_brush() makes the
  // press's one).
  const size_t shown = preview_.shown_samples();
  const glm::vec3 ball(radius, settings_.hardness, brush_strength_);
  bool extended = false;
  if (!brush_mirror_ && preview_.active() && shown > 0 && shown < brush_path_.size() &&
      ball == preview_ball_) {
    // Redoes only what the segments from the last shown sample on reach,
    // reading the material as it was before the stroke around them.
    auto extend = [&]<class Options>(
                      Options, int (*read_margin)(const Options&),
                      int64_t (*stroke_part)(core::Volume&, core::Sculptor&,
                                             std::span<const core::StrokeSample>, const Options&,
                                             const core::Box&, const core::Volume&)) {
      const std::span<const core::StrokeSample> tail = std::span(brush_path_).subspan(shown - 1);
      const core::Box part = path_brush_reach(*volume_, tail, radius, std::nullopt);
      const auto options = ball_brush_options<Options>(radius, settings_.hardness, brush_strength_);
      const int margin = read_margin(options);
      const core::Box read = core::intersect(core::Box{part.lo - margin, part.hi + margin},
                                             core::Box{glm::ivec3(0), volume_->dims()});
      preview_.extend(*volume_, read, brush_path_.size(), [&](const core::Volume& before) {
        core::Sculptor scratch(*volume_);
        return stroke_part(*volume_, scratch, brush_path_, options, part, before);
      });
      extended = true;
    };
    switch (brush_) {
      // A voxel's result is its weight's (the largest over the path;
      // pinching, with the path's nearest point) and the material around it.
      case PathBrush::kSmooth:
        extend(core::SmoothBrushOptions{}, core::smooth_read_margin, core::smooth_stroke_part);
        break;
      case PathBrush::kInflate:
        extend(core::InflateBrushOptions{}, core::inflate_read_margin, core::inflate_stroke_part);
        break;
      case PathBrush::kPinch:
        extend(core::PinchBrushOptions{}, core::pinch_read_margin, core::pinch_stroke_part);
        break;
      // Clay and flatten fit a plane to the whole path, and grab drags what
      // lay under the path's start: their previews start again.
      case PathBrush::kClay:
      case PathBrush::kFlatten:
      case PathBrush::kGrab:
        break;
    }
  }
  if (extended) {
    ++counters_.brush_previews_extended;
  } else {
    preview_.show(*volume_, region, brush_path_.size(), [&] {
      core::Sculptor scratch(*volume_);
      return path_brush_stroke(*volume_, scratch, brush_, brush_path_, radius, settings_.hardness,
                               brush_strength_, brush_mirror_);
    });
  }
  ++counters_.brush_previews;
  preview_ball_ = ball;
  preview_ended_ns_ = hal::monotonic_ns();
  preview_took_ns_ = preview_ended_ns_ - start_ns;
}

bool StationLoop::stroke_sculpts_as_set() const {
  return stroke_options_.mode == settings_.mode && stroke_options_.strength == settings_.strength &&
         stroke_options_.accumulate == settings_.accumulate;
}

std::optional<PathBrush> StationLoop::path_brush() const {
  if (settings_.brush) return path_brush_of(*settings_.brush);
  if (settings_.mode == core::SculptMode::kSmooth && tool_->sphere_radius_vox > 0.0f)
    return PathBrush::kSmooth;
  return std::nullopt;
}

std::optional<bool> StationLoop::stand_in_carves() const {
  // The modes scale the tool by the strength first: below 1 a dab leaves
  // less than the whole tool, and a path brush or smoothing something else.
  if (settings_.strength < 1.0f || path_brush()) return std::nullopt;
  switch (settings_.mode) {
    case core::SculptMode::kAdd:
    case core::SculptMode::kUnion:
      return false;
    case core::SculptMode::kSubtract:
    case core::SculptMode::kDifference:
      // Balls only. A carving stand-in draws the tool's far side behind
      // the clay as the hole's wall, which it is only where it lies inside
      // the clay; a box carved astride an edge of the clay opens through to
      // what is behind, and its stand-in showed a wall there (found with
      // pictures of a 50-voxel cube). A ball rarely reaches through.
      if (tool_->sphere_radius_vox > 0.0f) return true;
      break;
    case core::SculptMode::kSmooth:
      break;
  }
  return std::nullopt;
}

std::vector<hal::Dab> StationLoop::stand_in_copies(const std::vector<hal::Dab>& dabs) {
  // A press sweeps the tool from dab to dab (core/sculpt/stroke.h); copies
  // of it an eighth of its size apart show the sweep: the scallops between
  // them are under a hundredth of the tool's radius deep.
  const float step = std::max(1.0f, tool_size() / 8.0f);
  constexpr int kMostCopiesBetween = 32;
  std::vector<hal::Dab> copies;
  copies.reserve(dabs.size() * 3);
  for (const hal::Dab& d : dabs) {
    if (stand_in_last_) {
      const float gap = glm::distance(stand_in_last_->position, d.position);
      const int n = std::min(kMostCopiesBetween, static_cast<int>(std::ceil(gap / step)));
      for (int i = 1; i < n; ++i) {
        const float t = static_cast<float>(i) / static_cast<float>(n);
        hal::Dab& c = copies.emplace_back(d);
        c.position = glm::mix(stand_in_last_->position, d.position, t);
        c.orientation = glm::slerp(stand_in_last_->orientation, d.orientation, t);
      }
    }
    copies.push_back(d);
    stand_in_last_ = d;
  }
  return copies;
}

void StationLoop::sculpt(const std::vector<hal::Dab>& dabs) {
  // Shown before sculpting, which takes milliseconds for a big tool.
  if (stand_ins_ != nullptr && !dabs.empty()) {
    if (const std::optional<bool> carves = stand_in_carves()) {
      if (stand_in_tool_.valid()) stand_ins_->set_tool(stand_in_tool_.get());
      stand_ins_ns_ =
          stand_ins_->add(stand_in_copies(dabs), tool_version_, settings_.mirror, *carves);
      counters_.dabs_stood_in += static_cast<int64_t>(dabs.size());
    } else {
      stand_in_last_.reset();
    }
  }
  // A fast move's dabs that continue the open swept stroke go to it together:
  // each brick they reach is combined, undo-copied and encoded once, not once
  // a dab, and the material is byte for byte the same (SweptStroke::add()).
  std::vector<core::StrokeSample> pending;
  auto flush = [&] {
    if (pending.empty()) return;
    stroke_->add(pending);
    pending.clear();
  };
  for (const hal::Dab& d : dabs) {
    ++counters_.dabs;
    const core::StrokeSample sample{d.position, d.orientation};
    if (stroke_ && !path_brush() && settings_.mode != core::SculptMode::kSmooth &&
        stroke_sculpts_as_set()) {
      pending.push_back(sample);
      stroke_last_ = sample;
      continue;
    }
    flush();
    if (const std::optional<PathBrush> brush = path_brush()) {
      if (stroke_ ||
          (!brush_path_.empty() && (brush_ != *brush || brush_strength_ != settings_.strength))) {
        interrupt_stroke();
      }
      if (brush_path_.empty()) {
        brush_ = *brush;
        brush_strength_ = settings_.strength;
        brush_mirror_ = settings_.mirror;
        if (resume_stroke_) brush_path_.push_back(stroke_last_);
        resume_stroke_ = false;
      }
      brush_path_.push_back(sample);
      stroke_last_ = sample;
      if (options_.preview_brushes &&
          BrushPreview::due(brush_path_.size(), preview_.shown_samples()))
        show_brush_preview();
      continue;
    }
    if (!brush_path_.empty()) interrupt_stroke();
    if (settings_.mode == core::SculptMode::kSmooth) {
      stroke_.reset();
      core::Dab dab;
      dab.position_vox = d.position;
      dab.orientation = d.orientation;
      dab.mode = settings_.mode;
      dab.strength = settings_.strength;
      sculptor_->dab(dab);
      continue;
    }
    if (stroke_ && !stroke_sculpts_as_set()) interrupt_stroke();
    if (!stroke_) {
      stroke_options_ = {settings_.mode, settings_.strength, settings_.accumulate};
      stroke_ = std::make_unique<core::SweptStroke>(*sculptor_, stroke_options_);
      // After an interruption the rest of the press sweeps on from where
      // the tool was, not from a gap.
      if (resume_stroke_) stroke_->add(stroke_last_);
      resume_stroke_ = false;
    }
    stroke_->add(sample);
    stroke_last_ = sample;
  }
  flush();
}

void StationLoop::handle(const hal::InputEvent& e) {
  settle();
  switch (e.kind) {
    case hal::InputKind::kMotion: {
      ++counters_.motion_samples;
      integrator_.update(e);
      // A tool reaches at most its largest size past the volume: farther out
      // it sculpts nothing, and a device held at full push would otherwise
      // drive the pose (and the stroke's dabs behind it) out without bound.
      const glm::vec3 margin(sim::kMaxToolSizeVox + 1.0f);
      integrator_.clamp_position(-margin, glm::vec3(volume_->dims()) + margin);
      if (settings_.touch && !settings_.sheet_editing) {
        touch_moved(e);
      } else {
        tool_moved();
      }
      break;
    }
    case hal::InputKind::kButton:
      if (e.button == 0) {
        e.pressed ? press() : release();
      } else if (e.button == 1 && e.pressed) {
        settings_.mode = settings_.mode == core::SculptMode::kAdd ? core::SculptMode::kSubtract
                                                                  : core::SculptMode::kAdd;
        settings_.brush.reset();
      } else if (e.button == kClutchButton) {
        clutch_button_ = e.pressed;
        apply_clutch();
      }
      break;
    case hal::InputKind::kDisconnected:
      ++counters_.disconnects;
      release();
      integrator_.end_stream(e.device_id);
      break;
    case hal::InputKind::kTrackingLost:
      // The stroke ends where the tracker was last seen (no streak to where
      // it is found again), and the next pose re-anchors instead of jumping.
      ++counters_.tracking_losses;
      release();
      integrator_.lose_tracking();
      break;
    case hal::InputKind::kConnected:
      // A device plugged in again reports through a new pipeline, its
      // integral from zero: the tool goes on from where it is.
      integrator_.start_stream(e.device_id);
      break;
    case hal::InputKind::kBattery:
      break;
  }
}

void StationLoop::apply_clutch() {
  integrator_.set_clutch(clutch_key_ || clutch_button_);
}

int64_t StationLoop::update_mesh() {
  if (!options_.mesh) return 0;
  return mesh_.update(*volume_).bricks_meshed;
}

}  // namespace sculpt::station
