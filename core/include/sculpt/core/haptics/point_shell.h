#pragma once
// A tool's surface as points with normals, for tool-shaped contact (McNeely,
// Puterbaugh & Troy, "Six degree-of-freedom haptic rendering using voxel
// sampling", SIGGRAPH 1999: the moving object is a point shell, the static
// one a voxel map; here the static one is the material's distance patch).
//
// The points are the crossings of the tool density's 127.5 iso-surface with
// the tool grid's edges (exact: the trilinear density is linear along an
// edge), so any tool (a cube, a ring, a sculpture made a tool) gets a shell
// as fine as its voxels. Positions are in tool voxels relative to the pivot;
// normals point out of the tool.

#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/core/tool/tool.h"

namespace sculpt::core {

struct PointShell {
  /// Surface points relative to the tool's pivot, tool voxels.
  std::vector<glm::vec3> points;
  /// Outward unit normals of the tool at the points.
  std::vector<glm::vec3> normals;
  /// Largest distance of a point from the pivot (the tool's reach), voxels.
  float reach_vox = 0.0f;
};

/// The point shell of `tool`.
PointShell make_point_shell(const Tool& tool);

}  // namespace sculpt::core
