#include "render/gl/scene_renderer.h"

#include <algorithm>
#include <chrono>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "sculpt/core/distance/surface_normals.h"
#include "sculpt/core/mesh/mesh.h"
#include "sculpt/station/view/tool_outline.h"

namespace sculpt::station::gl {
namespace {

constexpr const char* kLitVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 model;
uniform mat4 view_projection;
out vec3 world_position;
out vec3 world_normal;
void main() {
  vec4 p = model * vec4(position, 1.0);
  world_position = p.xyz;
  world_normal = mat3(model) * normal;
  gl_Position = view_projection * p;
}
)";

// Studio lighting: a warm key light from the upper left, a cool fill from the
// right, a rim light from behind, and a sky/ground ambient term.
constexpr const char* kLitFragment = R"(#version 330 core
in vec3 world_position;
in vec3 world_normal;
uniform vec3 eye;
uniform vec4 colour;
out vec4 fragment;
void main() {
  vec3 n = normalize(world_normal);
  if (!gl_FrontFacing) n = -n;
  vec3 v = normalize(eye - world_position);
  vec3 key = normalize(vec3(-0.5, 0.8, 0.6));
  vec3 fill = normalize(vec3(0.7, 0.2, 0.4));
  // Powers by multiplying: llvmpipe's pow() is an exp2(log2()) whose
  // polynomials cost more than the rest of the shading together.
  float facing = 1.0 - max(dot(n, v), 0.0);
  float rim = facing * facing * facing;
  float ambient = mix(0.18, 0.32, 0.5 + 0.5 * n.y);
  float h = max(dot(n, normalize(key + v)), 0.0);
  float h5 = h * h;
  h5 = h5 * h5 * h;
  float h20 = h5 * h5;
  h20 = h20 * h20;
  float spec = h20 * h20;  // h^40
  vec3 c = colour.rgb * (ambient + 0.75 * max(dot(n, key), 0.0) * vec3(1.0, 0.96, 0.9) +
                         0.3 * max(dot(n, fill), 0.0) * vec3(0.85, 0.9, 1.0)) +
           0.25 * spec + 0.25 * rim * vec3(0.9, 0.95, 1.0);
  fragment = vec4(c, colour.a);
}
)";

constexpr const char* kFlatVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
uniform mat4 view_projection;
void main() { gl_Position = view_projection * vec4(position, 1.0); }
)";

constexpr const char* kFlatFragment = R"(#version 330 core
uniform vec4 colour;
out vec4 fragment;
void main() { fragment = colour; }
)";

// Distance-field normals: at most this much re-shading per frame.
constexpr int64_t kRefineBudgetNs = 4'000'000;
const glm::vec3 kClay(0.80f, 0.70f, 0.60f);

glm::vec3 mode_colour(core::SculptMode mode) {
  switch (mode) {
    case core::SculptMode::kAdd:
    case core::SculptMode::kUnion:
      return {0.35f, 0.75f, 0.40f};
    case core::SculptMode::kSubtract:
    case core::SculptMode::kDifference:
      return {0.85f, 0.35f, 0.30f};
    case core::SculptMode::kSmooth:
      return {0.35f, 0.55f, 0.90f};
  }
  return {0.8f, 0.8f, 0.8f};
}

// The centre of a mesh's bounding box (0 for an empty mesh, whose bounds
// are inverted).
glm::vec3 bounds_centre(const core::Mesh& mesh) {
  if (mesh.positions.empty()) return glm::vec3(0.0f);
  const core::MeshBounds b = core::mesh_bounds(mesh);
  return 0.5f * (b.lo + b.hi);
}

}  // namespace

Result<std::unique_ptr<SceneRenderer>> SceneRenderer::create() {
  std::unique_ptr<SceneRenderer> r(new SceneRenderer());
  auto lit = ShaderProgram::build(kLitVertex, kLitFragment, "lit");
  if (!lit) return lit.error();
  auto flat = ShaderProgram::build(kFlatVertex, kFlatFragment, "flat");
  if (!flat) return flat.error();
  r->lit_ = std::move(lit).value();
  r->flat_ = std::move(flat).value();
  glGenVertexArrays(1, &r->line_vao_);
  glGenBuffers(1, &r->line_vbo_);
  glBindVertexArray(r->line_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, r->line_vbo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
  glBindVertexArray(0);
  return r;
}

SurfaceSync SceneRenderer::sync_surface(const core::Volume* volume, const SurfaceSnapshot& surface,
                                        bool whole) {
  const SurfaceSync sync = upload_surface(surface);
  if (volume != nullptr) reshade(*volume, whole);
  return sync;
}

SurfaceSync SceneRenderer::upload_surface(const SurfaceSnapshot& surface) {
  SurfaceSync sync;
  visible_.clear();
  const auto& bricks = surface.bricks();
  std::erase_if(slots_, [&](const auto& slot) { return !bricks.contains(slot.first); });
  for (const auto& [index, b] : bricks) {
    Slot& slot = slots_[static_cast<uint64_t>(index)];
    if (slot.stamp != b.version) {
      slot.mesh.upload(b.mesh->mesh);
      slot.source = b.mesh;
      slot.distance_normals = false;
      slot.stamp = b.version;
      slot.centre = bounds_centre(b.mesh->mesh);
      ++sync.uploaded;
    }
    visible_.push_back({&slot.mesh, slot.centre});
    sync.triangles += slot.mesh.triangles();
  }
  return sync;
}

// Re-shades slots with the distance field's normals, in the slots' order,
// for at most kRefineBudgetNs (every slot when `whole`).
void SceneRenderer::reshade(const core::Volume& volume, bool whole) {
  if (!distance_normals_) return;
  const auto start = std::chrono::steady_clock::now();
  for (auto& [index, slot] : slots_) {
    if (slot.distance_normals) continue;
    core::Mesh smooth = slot.source->mesh;
    core::set_normals_from_surface_distance(volume, smooth);
    slot.mesh.upload(smooth);
    slot.distance_normals = true;
    if (!whole &&
        std::chrono::steady_clock::now() - start > std::chrono::nanoseconds(kRefineBudgetNs))
      break;
  }
}

void SceneRenderer::set_distance_normals(bool on) {
  if (on == distance_normals_) return;
  distance_normals_ = on;
  // On: the uploaded meshes (the mesher's normals) are re-shaded by
  // reshade(). Off: the re-shaded ones go back to the mesher's.
  for (auto& [brick, slot] : slots_) {
    if (!on && slot.distance_normals) slot.stamp = ~uint64_t{0};
    slot.distance_normals = false;
  }
}

void SceneRenderer::show_mesh(const core::Mesh& mesh) {
  single_mesh_.upload(mesh);
  visible_.assign(1, {&single_mesh_, glm::vec3(0.0f)});
}

void SceneRenderer::set_sheet(const core::Mesh& mesh, uint64_t version, bool editing) {
  sheet_editing_ = editing;
  if (version == sheet_version_) return;
  sheet_version_ = version;
  sheet_mesh_.upload(mesh);
}

void SceneRenderer::set_tool(const core::Tool& tool, uint64_t version) {
  if (version == tool_version_) return;
  tool_version_ = version;
  tool_pivot_ = tool.pivot;
  tool_mesh_.upload(window_tool_outline(tool));
}

void SceneRenderer::set_stand_in_tool(const DabStandIns::ToolMesh& tool) {
  if (tool.version == stand_in_version_ || !tool.mesh || !tool.coarse) return;
  stand_in_version_ = tool.version;
  stand_in_pivot_ = tool.pivot;
  stand_in_mesh_.upload(*tool.mesh);
  stand_in_coarse_.upload(*tool.coarse);
}

void SceneRenderer::draw_lines(const std::vector<glm::vec3>& points, glm::vec4 colour,
                               const glm::mat4& mvp) {
  flat_.use();
  flat_.set("view_projection", mvp);
  flat_.set("colour", colour);
  glBindVertexArray(line_vao_);
  glBindBuffer(GL_ARRAY_BUFFER, line_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(points.size() * sizeof(glm::vec3)),
               points.data(), GL_STREAM_DRAW);
  glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(points.size()));
}

void SceneRenderer::draw_haptics(const SceneView& view, const HapticOverlay& overlay) {
  const glm::mat4 vp = view.projection * view.view;
  // Seen through the clay: the device sinks into it while the proxy rests
  // on top, and that is what the sculptor needs to see.
  glDisable(GL_DEPTH_TEST);
  draw_lines(overlay.proxy, {0.95f, 0.85f, 0.35f, 1.0f}, vp);
  if (!overlay.ghost.empty()) draw_lines(overlay.ghost, {0.55f, 0.55f, 0.60f, 1.0f}, vp);
  draw_lines(overlay.device, {0.90f, 0.90f, 0.95f, 1.0f}, vp);
  if (!overlay.force.empty()) draw_lines(overlay.force, {1.0f, 0.45f, 0.15f, 1.0f}, vp);
  glEnable(GL_DEPTH_TEST);
}

void SceneRenderer::draw_box(const SceneView& view, glm::vec3 lo, glm::vec3 hi, glm::vec4 colour) {
  std::vector<glm::vec3> edges;
  for (int a = 0; a < 3; ++a)
    for (int j = 0; j < 4; ++j) {
      glm::vec3 p = lo;
      p[(a + 1) % 3] = (j & 1) ? hi[(a + 1) % 3] : lo[(a + 1) % 3];
      p[(a + 2) % 3] = (j & 2) ? hi[(a + 2) % 3] : lo[(a + 2) % 3];
      glm::vec3 q = p;
      q[a] = hi[a];
      edges.insert(edges.end(), {p, q});
    }
  glDisable(GL_DEPTH_TEST);
  draw_lines(edges, colour, view.projection * view.view);
  glEnable(GL_DEPTH_TEST);
}

void SceneRenderer::draw_tool_copies(std::span<const DabStandIn> stand_ins, bool carving) {
  // Past a budget of triangles (about what the clay itself holds), the
  // coarser mesh: tens of a big tool's copies waiting at once would
  // otherwise make the frames that show them several times longer.
  constexpr int64_t kTriangleBudget = 200'000;
  const int64_t copies = static_cast<int64_t>(stand_ins.size());
  const GpuMesh& mesh =
      copies * stand_in_mesh_.triangles() <= kTriangleBudget ? stand_in_mesh_ : stand_in_coarse_;
  for (const DabStandIn& s : stand_ins) {
    if (s.carves != carving || s.tool_version != stand_in_version_) continue;
    for (const bool reflected : {false, true}) {
      if (reflected && !s.mirror) continue;
      lit_.set("model", stand_in_model(s, stand_in_pivot_, reflected));
      // A reflection turns the triangles' winding over, and so which side
      // is the front.
      glFrontFace(reflected ? GL_CW : GL_CCW);
      mesh.draw();
    }
  }
  glFrontFace(GL_CCW);
}

void SceneRenderer::draw_stand_ins(std::span<const DabStandIn> stand_ins) {
  if (stand_in_mesh_.empty() || stand_ins.empty()) return;
  // Adding: the tool's mesh where each dab put it, drawn as clay, is the
  // picture of the clay after them (the visible surface of a union).
  draw_tool_copies(stand_ins, /*carving=*/false);
  const bool carving =
      std::any_of(stand_ins.begin(), stand_ins.end(), [](const DabStandIn& s) { return s.carves; });
  if (carving) {
    // Carving: where the clay's visible surface lies inside a tool, the
    // tool's far side behind it is the wall of the hole. Inside is counted
    // in the stencil: a tool face in front of the clay's surface enters
    // (front) or leaves (back) the tool on the way to it.
    // (The frame's clear left the stencil at 0.)
    glEnable(GL_STENCIL_TEST);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    glStencilFunc(GL_ALWAYS, 0, 0xff);
    glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_KEEP, GL_INCR_WRAP);
    glStencilOpSeparate(GL_BACK, GL_KEEP, GL_KEEP, GL_DECR_WRAP);
    draw_tool_copies(stand_ins, true);
    // The far sides there: of a stroke's overlapping tools, the farthest
    // one is where their union ends along the ray.
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    glStencilFunc(GL_NOTEQUAL, 0, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT);
    glDepthFunc(GL_GREATER);
    draw_tool_copies(stand_ins, true);
    glDepthFunc(GL_LESS);
    glCullFace(GL_BACK);
    glDisable(GL_STENCIL_TEST);
  }
  lit_.set("model", glm::mat4(1.0f));
}

void SceneRenderer::warm_up(int width, int height) {
  // A cube of side 2 about the origin, seen from outside: each pass draws
  // fragments (a state's code may be made when it first shades one).
  core::Mesh cube;
  for (int i = 0; i < 8; ++i)
    cube.positions.emplace_back((i & 1) ? 1.0f : -1.0f, (i & 2) ? 1.0f : -1.0f,
                                (i & 4) ? 1.0f : -1.0f);
  cube.normals = cube.positions;
  cube.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                    {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  GpuMesh clay, stand_in, stand_in_coarse, sheet, tool;
  for (GpuMesh* m : {&clay, &stand_in, &stand_in_coarse, &sheet, &tool})
    m->upload(cube);
  // The renderer's own meshes step aside for the cube's, and come back.
  std::swap(stand_in, stand_in_mesh_);
  std::swap(stand_in_coarse, stand_in_coarse_);
  std::swap(sheet, sheet_mesh_);
  std::swap(tool, tool_mesh_);
  std::vector<Drawn> drawn{{&clay, glm::vec3(0.0f)}};
  std::swap(drawn, visible_);
  const uint64_t stand_in_version = std::exchange(stand_in_version_, 0);
  const glm::vec3 tool_pivot = std::exchange(tool_pivot_, glm::vec3(0.0f));
  const glm::vec3 stand_in_pivot = std::exchange(stand_in_pivot_, glm::vec3(0.0f));

  SceneView view;
  view.eye = {0.0f, 0.0f, 6.0f};
  view.view = glm::lookAt(view.eye, glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
  view.projection = glm::perspective(glm::radians(45.0f), 1.0f, 0.1f, 100.0f);
  view.width = width;
  view.height = height;
  std::vector<DabStandIn> stand_ins(2);
  stand_ins[0].position = glm::vec3(0.3f);
  stand_ins[1].position = glm::vec3(-0.3f);
  stand_ins[1].carves = true;
  ToolDraw pointer;
  pointer.position = glm::vec3(0.5f);
  draw(view, pointer, glm::vec3(2.0f), stand_ins);
  HapticOverlay overlay;
  overlay.proxy = overlay.ghost = overlay.device =
      overlay.force = {glm::vec3(-1.0f), glm::vec3(1.0f)};
  draw_haptics(view, overlay);
  draw_box(view, glm::vec3(-1.0f), glm::vec3(1.0f), glm::vec4(1.0f));
  glFinish();
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);

  std::swap(stand_in, stand_in_mesh_);
  std::swap(stand_in_coarse, stand_in_coarse_);
  std::swap(sheet, sheet_mesh_);
  std::swap(tool, tool_mesh_);
  std::swap(drawn, visible_);
  stand_in_version_ = stand_in_version;
  tool_pivot_ = tool_pivot;
  stand_in_pivot_ = stand_in_pivot;
}

void SceneRenderer::draw(const SceneView& view, const ToolDraw& tool, glm::vec3 block,
                         std::span<const DabStandIn> stand_ins) {
  const glm::mat4 vp = view.projection * view.view;
  glViewport(0, 0, view.width, view.height);
  glClearColor(0.16f, 0.17f, 0.19f, 1.0f);
  // Depth and stencil together: the depth alone keeps the stencil bits that
  // share its 32-bit values, which llvmpipe does value by value (read, mask,
  // write), a tenth of its rasterising threads' time on the played demo;
  // both at once are a fill. The carving stand-ins count in the stencil
  // from this 0.
  glClearStencil(0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_BLEND);

  // The ground grid under the block, every 32 voxels, and the block's edges.
  std::vector<glm::vec3> grid;
  const float step = 32.0f;
  const float reach = std::max(block.x, block.z) * 1.5f;
  const glm::vec3 c = 0.5f * block;
  for (float t = -reach; t <= reach + 0.5f; t += step) {
    grid.insert(grid.end(), {{c.x + t, 0, c.z - reach},
                             {c.x + t, 0, c.z + reach},
                             {c.x - reach, 0, c.z + t},
                             {c.x + reach, 0, c.z + t}});
  }
  draw_lines(grid, {0.32f, 0.33f, 0.36f, 1.0f}, vp);
  std::vector<glm::vec3> edges;
  for (int a = 0; a < 3; ++a)
    for (int j = 0; j < 4; ++j) {
      glm::vec3 p(0.0f);
      p[(a + 1) % 3] = (j & 1) ? block[(a + 1) % 3] : 0.0f;
      p[(a + 2) % 3] = (j & 2) ? block[(a + 2) % 3] : 0.0f;
      glm::vec3 q = p;
      q[a] = block[a];
      edges.insert(edges.end(), {p, q});
    }
  draw_lines(edges, {0.55f, 0.57f, 0.62f, 1.0f}, vp);

  lit_.use();
  lit_.set("view_projection", vp);
  lit_.set("eye", view.eye);
  lit_.set("model", glm::mat4(1.0f));
  lit_.set("colour", glm::vec4(kClay, 1.0f));
  // The clay is closed and its triangles face outward: the back faces are
  // hidden behind front ones, and a software renderer (llvmpipe) spends
  // half its time shading them unless they are culled.
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  // Nearest first: a software renderer tests depth before it shades, so a
  // fragment hidden by nearer clay already drawn costs little.
  std::sort(visible_.begin(), visible_.end(), [&](const Drawn& a, const Drawn& b) {
    return glm::dot(a.centre - view.eye, a.centre - view.eye) <
           glm::dot(b.centre - view.eye, b.centre - view.eye);
  });
  for (const Drawn& d : visible_)
    d.mesh->draw();
  draw_stand_ins(stand_ins);
  glDisable(GL_CULL_FACE);  // a sheet is seen from both sides
  if (!sheet_mesh_.empty()) {
    // A sheet is not clay: a cool blue, brighter while it is being edited.
    lit_.set("colour", sheet_editing_ ? glm::vec4(0.35f, 0.62f, 0.95f, 1.0f)
                                      : glm::vec4(0.42f, 0.55f, 0.70f, 1.0f));
    sheet_mesh_.draw();
  }

  if (!tool.visible || tool_mesh_.empty()) return;
  // The GPU turns the tool's own mesh: the pivot goes to the tool position.
  const glm::mat4 model = glm::translate(glm::mat4(1.0f), tool.position) *
                          glm::mat4_cast(tool.orientation) *
                          glm::translate(glm::mat4(1.0f), -tool_pivot_);
  const glm::vec3 colour = mode_colour(tool.mode);
  lit_.set("model", model);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  // The ghost: the tool's parts hidden by the material, seen through it, which
  // is the footprint the next dab will leave.
  glDepthMask(GL_FALSE);
  glDepthFunc(GL_GREATER);
  lit_.set("colour", glm::vec4(colour, 0.35f));
  tool_mesh_.draw();
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  lit_.set("colour", glm::vec4(colour, tool.pressed ? 0.85f : 0.6f));
  tool_mesh_.draw();
  glDisable(GL_BLEND);
}

}  // namespace sculpt::station::gl
