#pragma once
// What the window draws for a dab before the dab's mesh is ready: the
// tool's own mesh where the dab put it (a stand-in), drawn as clay added or
// as the wall of the hole carved, until the mesher has meshed the change
// that holds the dab.
//
// Why: the sculptor must see a dab at once, however many bricks it
// re-meshes. The demo's 66-voxel ball takes 2-5 ms to sculpt, then re-meshes
// 50-85 bricks: 4.4 ms on two idle cores, 7-25 ms beside a software
// renderer, and the tool sticks meanwhile. Adding material at full strength
// leaves the union of the material and the tool (kUnion is max(m, f); kAdd
// sums them, which fills a little more where the two surfaces meet), and
// opaque surfaces drawn with a depth test show the visible surface of a
// union: the sculpture as it was plus the tool's mesh at the dab's pose is
// the picture of the sculpture after the dab, up to that fillet and the
// tool mesh's resolution (tests/station/app/dab_stand_ins_test.cpp bounds
// the difference). Carving at full strength leaves the material minus the
// tool: where the clay's visible surface lies inside the tool (a stencil
// count of the tool's faces in front of it), the tool's far side is the
// wall of the hole (render/gl/scene_renderer.cpp). A stand-in is published
// before its dab is sculpted, so it waits for neither sculpting nor
// meshing. Smoothing, a path brush or a weaker strength have no such
// picture and wait for their mesh.
//
// Thread safety: add() and handed_over() from the sculpting thread,
// showing() from the render thread; each holds a mutex for microseconds.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "sculpt/core/mesh/mesh.h"
#include "sculpt/core/sculpt/sculptor.h"
#include "sculpt/core/tool/tool.h"
#include "sculpt/hal/stroke/stroke_sampler.h"

namespace sculpt::station {

struct DabStandIn {
  glm::vec3 position{0.0f};  ///< where the tool's pivot was, voxels
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};
  /// Drawn a second time reflected across it, as the sculptor mirrors the dab.
  std::optional<core::MirrorPlane> mirror;
  uint64_t tool_version = 0;  ///< StationLoop::tool_version() of the dab's tool
  bool carves = false;        ///< the dab takes the tool away (else it adds it)
  uint64_t change = 0;        ///< the mesher's change holding the dab; 0: not handed over yet
};

/// The model matrix that puts a tool mesh (in the tool's voxel coordinates,
/// pivot at `pivot`) where `s` put the tool; `reflected`: its mirror image.
/// A reflection turns the triangles' winding over (drawn with it reversed).
glm::mat4 stand_in_model(const DabStandIn& s, glm::vec3 pivot, bool reflected);

class DabStandIns {
 public:
  /// Stand-ins kept at most (a dab and the copies of the tool its press
  /// swept it through, about three a dab); past it the oldest goes (counted
  /// in dropped()): its dab then shows when its mesh does.
  static constexpr size_t kMaxKept = 192;

  /// The sculpting thread is about to sculpt `dabs` with tool `tool_version`,
  /// adding it or carving it; returns when they were published
  /// (hal::monotonic_ns()).
  int64_t add(std::span<const hal::Dab> dabs, uint64_t tool_version,
              std::optional<core::MirrorPlane> mirror, bool carves = false);
  /// Everything sculpted so far went to the mesher as change `change` (or,
  /// when nothing was stored, `change` is the last one, already meshed).
  void handed_over(uint64_t change);
  /// The render thread's surface holds every change up to `meshed_change`:
  /// the stand-ins of those go, the rest are returned.
  std::vector<DabStandIn> showing(uint64_t meshed_change);

  /// The mesh stand-ins of tool `version` are drawn with (view/
  /// tool_outline.h, kStandInCells), made by the sculpting thread when the
  /// tool changes: a stand-in is then ready to draw when it is published.
  struct ToolMesh {
    uint64_t version = ~uint64_t{0};
    std::shared_ptr<const core::Mesh> mesh;  ///< in the tool's voxel coordinates
    /// The same from voxels averaged twice as far (kToolOutlineCells): what
    /// is drawn when many stand-ins wait at once (a big tool's stroke on a
    /// loaded machine), so that they do not slow the frames down.
    std::shared_ptr<const core::Mesh> coarse;
    glm::vec3 pivot{0.0f};  ///< the tool's pivot in them

    /// `tool`'s stand_in_outline() at both sizes, for tool version `version`.
    static ToolMesh of(const core::Tool& tool, uint64_t version);
  };
  void set_tool(ToolMesh tool);
  ToolMesh tool() const;

  size_t kept() const;
  int64_t dropped() const;

 private:
  mutable std::mutex mutex_;
  ToolMesh tool_;
  std::vector<DabStandIn> kept_;  // oldest first
  int64_t dropped_ = 0;
};

}  // namespace sculpt::station
