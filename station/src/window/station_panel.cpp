#include "window/station_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cstring>

#include "render/gl/gl_api.h"
#include "sculpt/core/tool/rotated_tool_cache.h"
#include "sculpt/station/settings/command_codec.h"
#include "sculpt/station/window/keymap.h"

namespace sculpt::station {
namespace {

void copy_path(char* out, size_t n, const std::string& s) {
  std::snprintf(out, n, "%s", s.c_str());
}

void tip(Action action) {
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", shortcut_label(action));
}

constexpr const char* kShapes[] = {"sphere", "cube", "cylinder", "ring", "cone"};
constexpr const char* kMirror[] = {"off", "x", "y", "z"};
constexpr const char* kInfluence[] = {"natural (smallest change)", "gaussian", "zone (refined)"};

}  // namespace

StationPanel::StationPanel(StationController& c) : c_(c) {
  copy_path(project_, sizeof(project_), c_.options().project.string());
  copy_path(mesh_, sizeof(mesh_), c_.options().mesh_export.string());
  copy_path(recording_, sizeof(recording_), c_.options().recording.string());
  copy_path(tool_file_, sizeof(tool_file_), (c_.options().tool_folder / "tool.nrrd").string());
  copy_path(mesh_file_, sizeof(mesh_file_), "tool.obj");
}

StationPanel::~StationPanel() {
  drop_thumbnails();
}

void StationPanel::draw(const FrameFigures& f, int64_t now) {
  figures_due_ = now - figures_at_ >= kFiguresEveryNs;
  if (figures_due_) figures_at_ = now;
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(330, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("Sculpt station");
  const StationSettings& s = c_.loop().settings();

  if (ImGui::CollapsingHeader("Device", ImGuiTreeNodeFlags_DefaultOpen)) {
    const DeviceStatus& d = c_.device_status();
    if (d.name.empty()) {
      ImGui::TextUnformatted("no 3D mouse: the mouse and keyboard sculpt");
    } else {
      ImGui::Text("%s (%s)%s", d.name.c_str(), d.backend.c_str(),
                  d.connected ? "" : " - unplugged");
      figure("%.0f reports/s", d.report_rate_hz);
      if (d.battery_percent >= 0)
        ImGui::Text("battery %d%%%s", d.battery_percent, d.charging ? " (charging)" : "");
    }
    int target = c_.device_target() == DeviceTarget::kTool ? 0 : 1;
    ImGui::RadioButton("moves the tool", &target, 0);
    ImGui::SameLine();
    ImGui::RadioButton("moves the camera", &target, 1);
    tip(Action::kToggleDeviceTarget);
    c_.set_device_target(target == 0 ? DeviceTarget::kTool : DeviceTarget::kCamera);
    bool touch = c_.loop().settings().touch;
    if (ImGui::Checkbox("touch mode: the tool rests on the clay", &touch)) c_.set_touch(touch, now);
    tip(Action::kToggleTouch);
    if (ImGui::Button("Tool to the centre")) c_.perform(Action::kCentreTool, now);
    tip(Action::kCentreTool);
    ImGui::SameLine();
    ImGui::TextDisabled(c_.loop().clutched() ? "clutch held" : "clutch: hold V");
    ImGui::SliderFloat("sensitivity", &sensitivity_, 0.1f, 4.0f, "%.2f");
    ImGui::SliderFloat("deadzone", &deadzone_, 0.0f, 0.5f, "%.2f");
    if (ImGui::Button("Save input settings")) (void)c_.save_input_settings(sensitivity_, deadzone_);
  }

  if (ImGui::CollapsingHeader("Tool", ImGuiTreeNodeFlags_DefaultOpen)) {
    int shape = static_cast<int>(s.shape);
    if (s.custom_tool) {
      ImGui::TextUnformatted(
          s.custom_source == CustomToolSource::kRegion  ? "tool: a region of the sculpture"
          : s.custom_source == CustomToolSource::kSheet ? "tool: the sheet's shell"
                                                        : "tool: from a file");
    }
    if (ImGui::Combo("shape", &shape, kShapes, IM_ARRAYSIZE(kShapes)) &&
        (shape != static_cast<int>(s.shape) || s.custom_tool)) {
      const auto picked = tool_shape_of_choice(static_cast<uint8_t>(shape));
      if (picked) c_.set_tool(*picked, s.size_a_vox, s.size_b_vox, now);
    }
    float a = s.size_a_vox, b = s.size_b_vox;
    if (s.custom_tool) {
      // A custom tool is resampled from the size it was made at.
      float scale = s.tool_scale;
      const glm::ivec3 d = c_.loop().tool().density.dims();
      ImGui::SliderFloat("size", &scale, 0.125f, 8.0f, "%.3g x", ImGuiSliderFlags_Logarithmic);
      if (ImGui::IsItemDeactivatedAfterEdit()) c_.set_tool_scale(scale, now);
      ImGui::Text("%d x %d x %d voxels", d.x, d.y, d.z);
    } else {
      ImGui::SliderFloat("size", &a, 1.0f, 64.0f, "%.1f vox");
      if (ImGui::IsItemDeactivatedAfterEdit()) c_.set_tool(s.shape, a, s.size_b_vox, now);
    }
    if (!s.custom_tool && s.shape != sim::ToolShape::kSphere && s.shape != sim::ToolShape::kCube) {
      ImGui::SliderFloat(s.shape == sim::ToolShape::kRing ? "tube" : "height", &b, 1.0f, 64.0f,
                         "%.1f vox");
      if (ImGui::IsItemDeactivatedAfterEdit()) c_.set_tool(s.shape, s.size_a_vox, b, now);
    }
    if (ImGui::Button("Use this sculpture as a tool")) c_.use_sculpture_as_tool(now);
    tip(Action::kUseSculptureAsTool);
    draw_tool_region(now);
    draw_tool_files(now);
    if (ImGui::Button("Hypertexture around the tool")) c_.hypertexture(now);
    tip(Action::kHypertexture);
    draw_morphology(now);

    // One choice: the three modes, then the ball brushes (a press applies the
    // brush to its whole path when it ends).
    constexpr const char* kModeLabels[] = {"add",     "subtract", "smooth", "clay",
                                           "flatten", "inflate",  "pinch",  "grab"};
    constexpr Action kBrushActions[] = {Action::kBrushClay, Action::kBrushFlatten,
                                        Action::kBrushInflate, Action::kBrushPinch,
                                        Action::kBrushGrab};
    int mode = s.brush                                 ? 3 + static_cast<int>(*s.brush)
               : s.mode == core::SculptMode::kSubtract ? 1
               : s.mode == core::SculptMode::kSmooth   ? 2
                                                       : 0;
    const int before = mode;
    for (int i = 0; i < IM_ARRAYSIZE(kModeLabels); ++i) {
      if (i % 4 != 0) ImGui::SameLine();
      ImGui::RadioButton(kModeLabels[i], &mode, i);
      if (i >= 3) tip(kBrushActions[i - 3]);
    }
    if (mode != before) {
      if (mode >= 3) {
        c_.set_brush(static_cast<BallBrush>(mode - 3), now);
      } else {
        c_.set_mode(mode == 0   ? core::SculptMode::kAdd
                    : mode == 1 ? core::SculptMode::kSubtract
                                : core::SculptMode::kSmooth,
                    now);
      }
    }
    bool accumulate = s.accumulate;
    if (ImGui::Checkbox("accumulate", &accumulate)) c_.set_accumulate(accumulate, now);
    tip(Action::kToggleAccumulate);
    float strength = s.strength;
    ImGui::SliderFloat("strength", &strength, 0.0f, 1.0f, "%.2f");
    if (ImGui::IsItemDeactivatedAfterEdit()) c_.set_strength(strength, now);
    float hardness = s.hardness;
    ImGui::SliderFloat("hardness", &hardness, 0.0f, 1.0f, "%.2f");
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("1: a hard edge; 0: a smooth bump (built-in tools)");
    if (ImGui::IsItemDeactivatedAfterEdit()) c_.set_hardness(hardness, now);
    float spacing = s.spacing;
    ImGui::SliderFloat("dab spacing", &spacing, 0.05f, 1.0f, "%.2f of size");
    if (ImGui::IsItemDeactivatedAfterEdit()) c_.set_spacing(spacing, now);
    int mirror = s.mirror ? s.mirror->axis + 1 : 0;
    if (ImGui::Combo("symmetry", &mirror, kMirror, IM_ARRAYSIZE(kMirror))) {
      c_.set_mirror(mirror == 0 ? std::nullopt : std::optional<int>(mirror - 1), now);
    }
  }

  if (ImGui::CollapsingHeader("NURBS sheet", ImGuiTreeNodeFlags_DefaultOpen)) draw_sheet(now);

  if (ImGui::CollapsingHeader("Edit and files", ImGuiTreeNodeFlags_DefaultOpen)) {
    if (ImGui::Button("Undo")) c_.undo(now);
    tip(Action::kUndo);
    ImGui::SameLine();
    if (ImGui::Button("Redo")) c_.redo(now);
    tip(Action::kRedo);
    draw_new_block(now);
    ImGui::InputText("project", project_, sizeof(project_));
    if (ImGui::Button("Save")) {
      c_.options().project = project_;
      (void)c_.save(project_);
    }
    tip(Action::kSave);
    ImGui::SameLine();
    if (ImGui::Button("Open")) (void)c_.open(project_);
    ImGui::InputText("mesh", mesh_, sizeof(mesh_));
    ImGui::SliderFloat("max error", &c_.options().mesh_export_max_error, 0.0f, 2.0f, "%.2f voxel");
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Export mesh may move the surface this far for fewer triangles (0: all)");
    if (ImGui::Button("Export mesh")) {
      c_.options().mesh_export = mesh_;
      (void)c_.export_mesh(mesh_);
    }
    tip(Action::kExportMesh);
    ImGui::InputText("session", recording_, sizeof(recording_));
    if (!c_.recording()) {
      if (ImGui::Button("Record")) {
        c_.options().recording = recording_;
        (void)c_.start_recording(recording_, now);
      }
    } else if (ImGui::Button("Stop recording")) {
      (void)c_.stop_recording();
    }
    tip(Action::kToggleRecording);
  }

  if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) {
    LodPolicy lod = c_.lod().policy();
    bool automatic = lod.fixed_level < 0;
    bool changed = ImGui::Checkbox("automatic level of detail", &automatic);
    if (automatic) {
      changed |=
          ImGui::SliderFloat("pixel error", &lod.max_pixel_error, 0.25f, 8.0f, "%.2f px per voxel");
      float budget = static_cast<float>(lod.frame_budget_ms);
      if (ImGui::SliderFloat("frame budget", &budget, 0.0f, 50.0f,
                             budget > 0 ? "%.0f ms" : "off")) {
        lod.frame_budget_ms = budget;
        changed = true;
      }
      if (lod.frame_budget_ms > 0) figure("coarsening bias %.2f", c_.lod().bias());
      if (changed && lod.fixed_level >= 0) lod.fixed_level = -1;
    } else {
      if (lod.fixed_level < 0) lod.fixed_level = 0;
      changed |= ImGui::SliderInt("level", &lod.fixed_level, 0, lod.max_level);
    }
    if (!automatic && changed && lod.fixed_level < 0) lod.fixed_level = 0;
    if (changed) c_.lod().set_policy(lod);
    bool smooth = c_.distance_normals();
    if (ImGui::Checkbox("normals from the distance field", &smooth))
      c_.set_distance_normals(smooth);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "the gradient of the distance to the sub-voxel surface: truer shading on bricks drawn at "
          "a coarse level");
    if (ImGui::Button("Frame the sculpture")) c_.perform(Action::kFrameView, now);
    tip(Action::kFrameView);
  }

  if (haptics_ != nullptr && ImGui::CollapsingHeader("Haptics", ImGuiTreeNodeFlags_DefaultOpen))
    draw_haptics(now);

  if (ImGui::CollapsingHeader("Figures", ImGuiTreeNodeFlags_DefaultOpen)) {
    figure("%.0f fps (%.1f ms), %lld triangles", f.fps, f.frame_ms,
           static_cast<long long>(f.triangles));
    const LatencyStats l = c_.recent_latency();
    figure("dab latency p50 %.2f ms, p99 %.2f ms", l.p50_us * 1e-3, l.p99_us * 1e-3);
    figure("dabs %lld, strokes %lld", static_cast<long long>(c_.loop().counters().dabs),
           static_cast<long long>(c_.loop().counters().strokes));
    // How often a non-ball tool's placement found its rotated voxels made
    // (the ball is swept without rotating).
    const core::RotatedToolCacheStats rc = c_.loop().rotation_cache_stats();
    figure("rotation cache: %.0f%% of %lld placements, %.0f%% of voxels",
           100.0 * rc.placement_hit_rate(), static_cast<long long>(rc.placements),
           100.0 * rc.voxel_hit_rate());
  }
  if (!c_.status().empty()) ImGui::TextWrapped("%s", c_.status().c_str());
  ImGui::End();
}

void StationPanel::figure(const char* format, ...) {
  std::string& line = figure_lines_[format];
  if (figures_due_ || line.empty()) {
    char text[256];
    va_list args;
    va_start(args, format);
    std::vsnprintf(text, sizeof(text), format, args);
    va_end(args);
    line = text;
  }
  ImGui::TextUnformatted(line.c_str());
}

void StationPanel::drop_thumbnails() {
  ++textures_version_;
  for (LibraryEntry& e : library_)
    if (e.texture != 0) glDeleteTextures(1, &e.texture);
  library_.clear();
}

void StationPanel::refresh_library() {
  drop_thumbnails();
  const StationController::ToolLibrary found =
      StationController::scan_tool_library(c_.options().tool_folder);
  library_unreadable_ = found.unreadable;
  library_scanned_ = true;
  for (const StationController::ToolFileEntry& t : found.tools) {
    LibraryEntry e;
    e.path = t.path.string();
    e.label = t.path.filename().string() + " (" + std::to_string(t.dims.x) + "x" +
              std::to_string(t.dims.y) + "x" + std::to_string(t.dims.z) + ")";
    glGenTextures(1, &e.texture);
    glBindTexture(GL_TEXTURE_2D, e.texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, t.thumbnail.width, t.thumbnail.height, 0, GL_RGB,
                 GL_UNSIGNED_BYTE, t.thumbnail.rgb.data());
    library_.push_back(std::move(e));
  }
  glBindTexture(GL_TEXTURE_2D, 0);
}

void StationPanel::draw_tool_files(int64_t now) {
  // The library is read once at the start (and on rescan or save), not per frame.
  if (!library_scanned_) refresh_library();
  if (!ImGui::TreeNode("Tool files and meshes")) return;
  ImGui::InputText("tool file", tool_file_, sizeof(tool_file_));
  if (ImGui::Button("Load tool")) c_.load_tool(tool_file_, now);
  ImGui::SameLine();
  if (ImGui::Button("Save tool") && c_.save_tool(tool_file_).ok()) refresh_library();
  ImGui::InputText("mesh", mesh_file_, sizeof(mesh_file_));
  ImGui::SliderInt("mesh tool size", &mesh_tool_edge_, 8, StationLoop::kMaxScaledToolEdge,
                   "%d vox");
  if (ImGui::Button("Import mesh as tool"))
    c_.import_mesh_as_tool(mesh_file_, mesh_tool_edge_, now);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("a closed OBJ, PLY, STL or GLB, voxelized");
  // The library: the tool folder's files, each a picture and a click to use it.
  ImGui::Text("library: %s", c_.options().tool_folder.string().c_str());
  ImGui::SameLine();
  if (ImGui::SmallButton("rescan")) refresh_library();
  if (library_.empty()) ImGui::TextDisabled("no tool files there yet (Save tool adds one)");
  for (size_t i = 0; i < library_.size(); ++i) {
    const LibraryEntry& e = library_[i];
    ImGui::PushID(static_cast<int>(i));
    const ImTextureID texture = reinterpret_cast<ImTextureID>(static_cast<intptr_t>(e.texture));
    if (ImGui::ImageButton(texture, ImVec2(48, 48))) {
      c_.load_tool(e.path, now);
      copy_path(tool_file_, sizeof(tool_file_), e.path);
    }
    ImGui::SameLine();
    ImGui::TextUnformatted(e.label.c_str());
    ImGui::PopID();
  }
  if (library_unreadable_ > 0)
    ImGui::TextDisabled("%d file(s) there are not tools", library_unreadable_);
  ImGui::TreePop();
}

void StationPanel::draw_morphology(int64_t now) {
  if (!ImGui::TreeNode("Offset and closing")) return;
  // The distance-field tools of `sculpt offset` and `sculpt close`, on the
  // whole sculpture, one undo step each. They compute in the background
  // (seconds on a big sculpture): one at a time, the status says when done.
  const bool computing = c_.loop().morphology_pending();
  ImGui::BeginDisabled(computing);
  ImGui::SliderFloat("offset by", &c_.offset_vox(), -16.0f, 16.0f, "%+.1f vox");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("outward when positive, inward when negative");
  if (ImGui::Button("Offset the sculpture")) c_.offset_sculpture(c_.offset_vox(), now);
  tip(Action::kOffsetSculpture);
  ImGui::SliderFloat("closing radius", &c_.closing_radius_vox(), 0.5f, 16.0f, "%.1f vox");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("fills gaps and dents narrower than twice the radius");
  if (ImGui::Button("Close the sculpture")) c_.close_sculpture(c_.closing_radius_vox(), now);
  tip(Action::kCloseSculpture);
  ImGui::EndDisabled();
  if (computing) ImGui::TextUnformatted(c_.status().c_str());
  ImGui::TreePop();
}

void StationPanel::ask_new_block() {
  ask_new_block_ = true;
}

void StationPanel::draw_new_block(int64_t now) {
  NewBlockOptions& block = c_.new_block_options();
  if (ImGui::TreeNode("New block")) {
    int dims[3] = {block.dims.x, block.dims.y, block.dims.z};
    if (ImGui::DragInt3("size", dims, 1.0f, StationController::kMinBlockSide,
                        StationController::kMaxBlockSide, "%d vox", ImGuiSliderFlags_AlwaysClamp))
      block.dims = {dims[0], dims[1], dims[2]};
    int fill = static_cast<int>(block.fill);
    ImGui::RadioButton("empty", &fill, 0);
    ImGui::SameLine();
    ImGui::RadioButton("full", &fill, 1);
    ImGui::SameLine();
    ImGui::RadioButton("clay slab", &fill, 2);
    block.fill = static_cast<BlockFill>(fill);
    if (ImGui::Button("New block...")) ask_new_block_ = true;
    tip(Action::kNewBlock);
    ImGui::TreePop();
  }
  // The sculpture goes for good (the undo history starts again): asked first.
  if (ask_new_block_) {
    ImGui::OpenPopup("Replace the sculpture?");
    ask_new_block_ = false;
  }
  if (ImGui::BeginPopupModal("Replace the sculpture?", nullptr,
                             ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("A new %d x %d x %d block replaces the sculpture.", block.dims.x, block.dims.y,
                block.dims.z);
    ImGui::TextUnformatted("This cannot be undone (save the project first to keep it).");
    if (ImGui::Button("Replace")) {
      c_.new_block(block, now);
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) {
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
}

void StationPanel::draw_tool_region(int64_t now) {
  if (!ImGui::TreeNode("Tool from a region")) return;
  const std::optional<core::Box>& region = c_.tool_region();
  if (ImGui::Button("From the material")) c_.tool_region_from_material();
  ImGui::SameLine();
  if (ImGui::Button("Around the tool")) c_.tool_region_around_tool();
  if (region) {
    ImGui::SameLine();
    if (ImGui::Button("Hide")) c_.clear_tool_region();
    tip(Action::kToggleToolRegion);
  }
  if (const std::optional<core::Box> r = c_.tool_region()) {
    // Each corner dragged (or typed, Ctrl+click) voxel by voxel, within the block.
    const glm::ivec3 dims = c_.loop().volume().dims();
    const int top = std::max({dims.x, dims.y, dims.z});
    int lo[3] = {r->lo.x, r->lo.y, r->lo.z};
    int hi[3] = {r->hi.x, r->hi.y, r->hi.z};
    bool changed = ImGui::DragInt3("low corner", lo, 0.25f, 0, top);
    changed |= ImGui::DragInt3("high corner", hi, 0.25f, 0, top);
    if (changed) c_.set_tool_region({{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}});
    const glm::ivec3 size = c_.tool_region()->size();
    ImGui::Text("%d x %d x %d voxels (a tool: at most %d a side)", size.x, size.y, size.z,
                StationController::kMaxToolEdge);
    if (ImGui::Button("Use region as tool")) c_.use_region_as_tool(now);
    tip(Action::kUseRegionAsTool);
  }
  ImGui::TreePop();
}

void StationPanel::draw_haptics(int64_t now) {
  HapticStation& h = *haptics_;
  const HapticFigures f = h.figures();
  const hal::ForceLimits& limits = h.device().limits();
  ImGui::Text("%s: %s", f.device.c_str(), f.running ? "running" : "stopped");
  if (!f.realtime_note.empty() && ImGui::IsItemHovered())
    ImGui::SetTooltip("%s", f.realtime_note.c_str());
  bool on = h.enabled();
  if (ImGui::Checkbox("force (K)", &on)) on ? h.enable() : h.drop();
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("off drops the force at once; on ramps it in over half a second");
  ImGui::SameLine();
  ImGui::TextDisabled("clutch: hold V");
  // Each setting restarts the loop when let go (the force ramps in again).
  ContactSettings s = h.contact_settings();
  bool changed = false;
  ImGui::SliderFloat("stiffness", &s.haptic.coupling.stiffness_n_per_mm, 0.05f,
                     limits.max_stiffness_n_per_mm, "%.2f N/mm");
  changed |= ImGui::IsItemDeactivatedAfterEdit();
  ImGui::SliderFloat("friction", &s.haptic.proxy.friction.static_coefficient, 0.0f, 1.0f, "%.2f");
  if (ImGui::IsItemDeactivatedAfterEdit()) {
    // Sliding grips a little less than resting does.
    s.haptic.proxy.friction.dynamic_coefficient = 0.8f * s.haptic.proxy.friction.static_coefficient;
    changed = true;
  }
  ImGui::SliderFloat("force scale", &s.force_scale, 0.0f, 1.0f, "%.2f");
  changed |= ImGui::IsItemDeactivatedAfterEdit();
  ImGui::SliderFloat("workspace scale", &s.workspace_scale, 0.25f, 8.0f, "%.2f x");
  changed |= ImGui::IsItemDeactivatedAfterEdit();
  if (changed) h.set_contact(s);
  // The loop's rate over the last second or so.
  if (now - haptic_since_ns_ > 1'000'000'000) {
    if (haptic_since_ns_ != 0)
      haptic_rate_hz_ = static_cast<double>(f.ticks - haptic_ticks_) * 1e9 /
                        static_cast<double>(now - haptic_since_ns_);
    haptic_ticks_ = f.ticks;
    haptic_since_ns_ = now;
  }
  figure("loop %.0f Hz%s, late ticks %lld of %lld", haptic_rate_hz_,
         f.realtime ? " (real-time)" : "", static_cast<long long>(f.late_ticks),
         static_cast<long long>(f.ticks));
  if (f.threads == 2)
    figure("standby thread on another core: %lld late wake-ups covered",
           static_cast<long long>(f.standby_rescues));
  figure("worst period %.2f ms, max force %.2f N, ramp %.0f%%", f.worst_period_us * 1e-3,
         f.max_force_n, f.ramp * 100.0f);
  const ContactRecord& contact = h.contact();
  figure("%s%s, force %.2f N", contact.contact ? "in contact" : "free",
         contact.clutched ? ", clutched" : "", glm::length(h.tick().force_n));
}

void StationPanel::draw_sheet(int64_t now) {
  const StationSettings& s = c_.loop().settings();
  const SheetEditor& sheet = c_.loop().sheet();
  if (!sheet.has_sheet()) {
    if (ImGui::Button("New sheet through the tool")) c_.new_sheet(now);
    tip(Action::kNewSheet);
    return;
  }
  const core::nurbs::NurbsSurface& surface = sheet.surface();
  ImGui::Text("bicubic, %d x %d control points", surface.count_u, surface.count_v);
  bool editing = s.sheet_editing;
  if (ImGui::Checkbox("presses drag the sheet", &editing)) c_.set_sheet_editing(editing, now);
  tip(Action::kToggleSheetEditing);
  int influence = static_cast<int>(s.sheet_drag.influence);
  float radius = static_cast<float>(s.sheet_drag.radius);
  bool changed = ImGui::Combo("influence", &influence, kInfluence, IM_ARRAYSIZE(kInfluence));
  if (influence == static_cast<int>(SheetInfluence::kGaussian)) {
    ImGui::SliderFloat("reach", &radius, 0.0f, 8.0f, "%.1f control points");
    changed |= ImGui::IsItemDeactivatedAfterEdit();
  } else if (influence == static_cast<int>(SheetInfluence::kZone)) {
    ImGui::SliderFloat("zone radius", &radius, 0.02f, 0.5f, "%.2f of the domain");
    changed |= ImGui::IsItemDeactivatedAfterEdit();
  }
  if (changed) c_.set_sheet_influence(static_cast<SheetInfluence>(influence), radius, now);
  if (sheet.last_residual() > 0)
    ImGui::Text("last drag: residual %.1e voxel", sheet.last_residual());
  float thickness = c_.sheet_thickness();
  if (ImGui::SliderFloat("shell", &thickness, 0.5f, 16.0f, "%.1f vox thick"))
    c_.set_sheet_thickness(thickness);
  if (ImGui::Button("Add to material")) c_.sheet_into_material(true, now);
  tip(Action::kSheetAddToMaterial);
  ImGui::SameLine();
  if (ImGui::Button("Cut from material")) c_.sheet_into_material(false, now);
  tip(Action::kSheetSubtractFromMaterial);
  if (ImGui::Button("Make it the tool")) c_.sheet_as_tool(now);
  tip(Action::kSheetAsTool);
  ImGui::SameLine();
  if (ImGui::Button("Export")) (void)c_.export_sheet(c_.options().sheet_export);
  tip(Action::kExportSheet);
  ImGui::SameLine();
  if (ImGui::Button("Remove")) c_.remove_sheet(now);
  tip(Action::kRemoveSheet);
}

}  // namespace sculpt::station
