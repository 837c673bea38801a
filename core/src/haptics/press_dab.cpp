#include "sculpt/core/haptics/press_dab.h"

#include <algorithm>

#include <glm/geometric.hpp>

namespace sculpt::core {

std::optional<glm::vec3> pressed_dab_position(glm::vec3 proxy_vox, glm::vec3 normal,
                                              glm::vec3 force_n, bool contact,
                                              const PressOptions& options) {
  if (!contact) return std::nullopt;
  // The material pushes the hand out along the normal: that is the push.
  const float push_n = glm::dot(force_n, normal);
  if (push_n <= options.threshold_n) return std::nullopt;
  const float depth =
      std::min((push_n - options.threshold_n) * options.depth_vox_per_n, options.max_depth_vox);
  return proxy_vox - depth * normal;
}

}  // namespace sculpt::core
