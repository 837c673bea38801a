#pragma once
// Sculpting with force: in add and subtract modes a dab lands where the proxy
// is, pressed into the material along the contact normal by a depth that
// grows with the push. A sculptor resting the tool on the clay carves
// nothing; pushing harder than the threshold carves deeper, and the material
// resists (the proxy stays on the surface, so the spring grows with the
// push). With a 3D mouse in touch mode the push is the cap's deflection
// scaled to newtons by the station. A pure function of its inputs: replays
// carve the same.

#include <optional>

#include <glm/vec3.hpp>

namespace sculpt::core {

struct PressOptions {
  /// Push along the normal below which nothing is carved, N.
  float threshold_n = 1.0f;
  /// Depth per newton beyond the threshold, voxels/N.
  float depth_vox_per_n = 1.0f;
  /// Deepest press, voxels.
  float max_depth_vox = 4.0f;
};

/// The dab position for a proxy at `proxy_vox` with outward normal `normal`
/// and the force on the hand `force_n`; nullopt out of contact or under the
/// threshold.
std::optional<glm::vec3> pressed_dab_position(glm::vec3 proxy_vox, glm::vec3 normal,
                                              glm::vec3 force_n, bool contact,
                                              const PressOptions& options);

}  // namespace sculpt::core
