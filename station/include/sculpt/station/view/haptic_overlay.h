#pragma once
// What the window draws for a force device (DESIGN.md §5a), as line segments
// in material voxels: the proxy (where the tool rests) as three great circles,
// the device point as a small cross with, when it has sunk into the material
// away from the proxy, a ghost of the tool's sphere there, and the force on
// the hand as an arrow from the proxy. GL-free: the renderer draws the
// segments, tests check them.

#include <vector>

#include <glm/vec3.hpp>

namespace sculpt::station {

struct HapticOverlayInput {
  glm::vec3 device_vox{0.0f};
  glm::vec3 proxy_vox{0.0f};
  float radius_vox = 1.0f;
  /// The force on the hand, N (device frame = the station's axes).
  glm::vec3 force_n{0.0f};
  /// Arrow length per newton, voxels.
  float arrow_vox_per_n = 4.0f;
};

struct HapticOverlay {
  /// Pairs of points: each two make one segment.
  std::vector<glm::vec3> proxy;
  std::vector<glm::vec3> ghost;  ///< empty while the device is at the proxy
  std::vector<glm::vec3> device;
  std::vector<glm::vec3> force;  ///< empty under 0.05 N
};

/// The ghost shows once the device is this far from the proxy, voxels.
inline constexpr float kGhostSeparationVox = 0.5f;

HapticOverlay haptic_overlay(const HapticOverlayInput& in);

}  // namespace sculpt::station
