#include "sculpt/core/haptics/point_shell.h"

#include <algorithm>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace sculpt::core {
namespace {

float density_at(const DenseGrid<uint8_t>& g, glm::ivec3 v) {
  v = glm::clamp(v, glm::ivec3(0), g.dims() - 1);
  return float(g.at(v.x, v.y, v.z));
}

glm::vec3 gradient_at(const DenseGrid<uint8_t>& g, glm::ivec3 v) {
  return 0.5f *
         glm::vec3(density_at(g, v + glm::ivec3(1, 0, 0)) - density_at(g, v - glm::ivec3(1, 0, 0)),
                   density_at(g, v + glm::ivec3(0, 1, 0)) - density_at(g, v - glm::ivec3(0, 1, 0)),
                   density_at(g, v + glm::ivec3(0, 0, 1)) - density_at(g, v - glm::ivec3(0, 0, 1)));
}

}  // namespace

PointShell make_point_shell(const Tool& tool) {
  PointShell shell;
  const DenseGrid<uint8_t>& g = tool.density;
  const glm::ivec3 dims = g.dims();
  for (int a = 0; a < 3; ++a) {
    glm::ivec3 step(0);
    step[a] = 1;
    for (int z = 0; z + step.z < dims.z; ++z)
      for (int y = 0; y + step.y < dims.y; ++y)
        for (int x = 0; x + step.x < dims.x; ++x) {
          const glm::ivec3 v{x, y, z};
          const float d0 = float(g.at(x, y, z));
          const float d1 = density_at(g, v + step);
          if ((d0 >= 128.0f) == (d1 >= 128.0f)) continue;
          const float t = (d0 - 127.5f) / (d0 - d1);
          const glm::vec3 gradient = glm::mix(gradient_at(g, v), gradient_at(g, v + step), t);
          const float length = glm::length(gradient);
          const glm::vec3 normal =
              length > 1e-3f ? -gradient / length : glm::vec3(step) * (d0 >= 128.0f ? 1.0f : -1.0f);
          const glm::vec3 p = glm::vec3(v) + t * glm::vec3(step) - tool.pivot;
          shell.points.push_back(p);
          shell.normals.push_back(normal);
          shell.reach_vox = std::max(shell.reach_vox, glm::length(p));
        }
  }
  return shell;
}

}  // namespace sculpt::core
