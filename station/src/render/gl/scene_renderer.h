#pragma once
// The station's OpenGL 3.3 core renderer: the sculpture from the per-brick
// mesh cache at a level of detail per brick, the tool from its own mesh
// turned on the GPU (not the discrete rotation the sculpting uses), a ghost
// of the part of the tool inside the material, the block's bounds and a
// ground grid, the NURBS sheet (two-sided), under simple studio lighting (key, fill, rim,
// sky/ground ambient). Needs a current GL 3.3 context; one thread.

#include <cstdint>
#include <memory>
#include <span>
#include <unordered_map>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>

#include "render/gl/gpu_mesh.h"
#include "render/gl/shader_program.h"
#include "sculpt/core/mesh/brick_mesh.h"
#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/sculpt/sculptor.h"
#include "sculpt/core/tool/tool.h"
#include "sculpt/station/app/dab_stand_ins.h"
#include "sculpt/station/view/haptic_overlay.h"
#include "sculpt/station/view/surface_mesher.h"

namespace sculpt::station::gl {

struct SceneView {
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};
  glm::vec3 eye{0.0f};
  int width = 1;  ///< framebuffer pixels
  int height = 1;
};

struct ToolDraw {
  bool visible = true;
  glm::vec3 position{0.0f};  ///< where the pivot is, voxels
  glm::quat orientation{1, 0, 0, 0};
  core::SculptMode mode = core::SculptMode::kAdd;
  bool pressed = false;
};

struct SurfaceSync {
  int64_t uploaded = 0;   ///< brick meshes sent to the GPU this time
  int64_t triangles = 0;  ///< triangles drawn per frame at the chosen levels
};

class SceneRenderer {
 public:
  static Result<std::unique_ptr<SceneRenderer>> create();

  /// Sends the brick meshes re-made since the last call to the GPU.
  /// `volume` is read for distance normals only; null when this frame may
  /// not read it (the sculpting thread holds it): re-shading then waits for
  /// a frame that may. `whole`: re-shade every brick now, however long it
  /// takes (a picture of this frame), instead of within the frame's budget.
  SurfaceSync sync_surface(const core::Volume* volume, const SurfaceSnapshot& surface,
                           bool whole = false);
  /// sync_surface()'s two halves, for a caller that holds the volume only
  /// part of the frame: the uploads read only `surface` (its meshes are
  /// never changed, mixed_level_mesh.h); re-shading reads the volume.
  SurfaceSync upload_surface(const SurfaceSnapshot& surface);
  void reshade(const core::Volume& volume, bool whole = false);
  /// Normals of the brick meshes: the density gradient (false, the mesher's)
  /// or the gradient of the distance to the sub-voxel surface (true;
  /// smoother). A changed brick is first drawn with the mesher's normals and
  /// re-shaded with the distance field's within a few milliseconds of each
  /// frame (kRefineBudgetNs), so sculpting stays as fast as without.
  void set_distance_normals(bool on);
  bool distance_normals() const { return distance_normals_; }
  /// Draws this one mesh as the surface instead (pictures of a result).
  void show_mesh(const core::Mesh& mesh);
  /// Remakes the tool's mesh when `version` differs from the last one given
  /// (StationLoop::tool_version).
  void set_tool(const core::Tool& tool, uint64_t version);
  /// The version of the tool set_tool() last outlined.
  uint64_t tool_version() const { return tool_version_; }
  /// The mesh stand-ins are drawn with, uploaded when its version moved.
  void set_stand_in_tool(const DabStandIns::ToolMesh& tool);
  /// The NURBS sheet's mesh (empty: no sheet), uploaded when `version`
  /// differs from the last one given; `editing` draws it highlighted.
  void set_sheet(const core::Mesh& mesh, uint64_t version, bool editing);
  /// Draws the scene; `stand_ins`: dabs not meshed yet, drawn as clay added
  /// or carved by the tool's mesh where each put it (app/dab_stand_ins.h;
  /// carving needs a stencil buffer).
  void draw(const SceneView& view, const ToolDraw& tool, glm::vec3 block_dims,
            std::span<const DabStandIn> stand_ins = {});
  /// Draws every kind of thing draw(), draw_haptics() and draw_box() draw
  /// (clay, adding and carving stand-ins, a sheet, the tool and its ghost,
  /// lines), a small cube each, into a `width` x `height` frame that is then
  /// cleared, and waits for it. A software renderer (Mesa's llvmpipe)
  /// makes its code for each state the first time it draws with it: 11-20
  /// ms more than a warm call here with Mesa's shader cache filled, 157-165
  /// ms on a machine's first run. Done once when the window opens, the
  /// first frames and the sculptor's first dab do not wait for it. Leaves
  /// the renderer as it found it.
  void warm_up(int width, int height);
  /// Over what draw() drew: a force device's proxy, device point, ghost and
  /// force arrow (view/haptic_overlay.h), drawn through the clay so the
  /// device is seen where it has sunk in.
  void draw_haptics(const SceneView& view, const HapticOverlay& overlay);
  /// The edges of the box [lo, hi] (voxels), drawn through the clay: the
  /// region the panel picks a tool from.
  void draw_box(const SceneView& view, glm::vec3 lo, glm::vec3 hi, glm::vec4 colour);

 private:
  SceneRenderer() = default;
  struct Slot {
    uint64_t stamp = ~uint64_t{0};
    GpuMesh mesh;
    std::shared_ptr<const core::BrickMesh> source;  // what was uploaded
    bool distance_normals = false;                  // re-shaded since the last upload
    glm::vec3 centre{0.0f};                         // of the mesh's bounds, voxels
  };
  // A mesh to draw and where it is: the clay is drawn nearest first.
  struct Drawn {
    const GpuMesh* mesh = nullptr;
    glm::vec3 centre{0.0f};
  };
  void draw_lines(const std::vector<glm::vec3>& points, glm::vec4 colour, const glm::mat4& mvp);
  // Dabs not meshed yet (app/dab_stand_ins.h), over the clay just drawn
  // with lit_ in use and back faces culled.
  void draw_stand_ins(std::span<const DabStandIn> stand_ins);
  // The tool's mesh where each adding (or carving) stand-in put it.
  void draw_tool_copies(std::span<const DabStandIn> stand_ins, bool carving);

  ShaderProgram lit_;
  ShaderProgram flat_;
  std::unordered_map<uint64_t, Slot> slots_;  // key: brick index
  std::vector<Drawn> visible_;
  uint64_t tool_version_ = ~uint64_t{0};
  glm::vec3 tool_pivot_{0.0f};
  GpuMesh tool_mesh_;
  GpuMesh stand_in_mesh_;    // the tool finer (view/tool_outline.h), drawn as clay
  GpuMesh stand_in_coarse_;  // and as the outline, when many wait
  uint64_t stand_in_version_ = ~uint64_t{0};
  glm::vec3 stand_in_pivot_{0.0f};
  GpuMesh single_mesh_;
  GpuMesh sheet_mesh_;
  uint64_t sheet_version_ = ~uint64_t{0};
  bool sheet_editing_ = false;
  bool distance_normals_ = false;
  GLuint line_vao_ = 0, line_vbo_ = 0;
};

}  // namespace sculpt::station::gl
