#pragma once
// The tool pose the HAL hands to the station: where the tool is, how it is
// turned, and when.

#include <cstdint>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

namespace sculpt::hal {

struct ToolPose {
  glm::vec3 position{0.0f};                       ///< world units (the core's voxel units)
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};  ///< unit quaternion, tool to world
  int64_t t_ns = 0;                               ///< monotonic ns of the sample that produced it
};

}  // namespace sculpt::hal
