#pragma once
// The god object (Zilles & Salisbury 1995), or proxy (Ruspini, Kolarov &
// Khatib 1997), of a sphere tool on the material's signed distance field
// (Salisbury & Tarr 1997: the constraint is an implicit surface).
//
// The proxy is where the tool would be if the material were rigid: it holds
// phi(proxy) >= r (r the tool's radius in voxels; 0 for a point). Each update
// moves it toward the device:
//   - freely by sphere tracing: no step is longer than phi - r, so no wall,
//     however thin, is crossed however far the device jumped;
//   - in contact, along the surface: the motion is projected onto the tangent
//     planes of the constraints met this update (up to three: a face, an edge,
//     a concave corner), taken in steps of at most a quarter voxel, each
//     pulled back onto phi = r + skin by Newton steps along the gradient.
// With friction (coulomb_friction.h) the sliding point is then held back.
//
// Units: material voxels. The update reads only the patch; it never
// allocates.

#include <glm/vec3.hpp>

#include "sculpt/core/haptics/coulomb_friction.h"
#include "sculpt/core/haptics/patch_snapshot.h"

namespace sculpt::core {

struct SphereProxyOptions {
  /// The tool's radius in voxels (0: a point). The patch's band must be at
  /// least band_for_sphere(radius_vox) (distance_patch.h).
  float radius_vox = 1.0f;
  /// The proxy rests this far outside phi = r, so contact does not flicker.
  float skin_vox = 0.01f;
  /// Longest step along the surface; small enough to follow a curve of a
  /// few voxels' radius and never to cross a wall.
  float slide_step_vox = 0.25f;
  /// Steps per update; what is left is taken at the next update.
  int max_steps = 32;
  CoulombFriction friction;
};

struct ProxyState {
  glm::vec3 position_vox{0.0f};
  /// Whether the proxy touches the material (and the device is behind it).
  bool contact = false;
  /// Outward unit normal of the material at the proxy (valid in contact).
  glm::vec3 normal{0.0f};
  /// Constraints in force at the end of the update (0-3).
  int active_constraints = 0;
  /// Whether friction let the proxy slide this update.
  bool sliding = false;
  /// Whether the patch's edge stopped the proxy (the patch must follow).
  bool at_patch_edge = false;
};

class SphereProxy {
 public:
  explicit SphereProxy(const SphereProxyOptions& options = {});

  /// Places the proxy at `position_vox` (where the tool is when contact
  /// begins, e.g. the device's position at start-up, outside the material).
  /// A position inside the material is pushed out along the gradient.
  void reset(const PatchSnapshot& field, glm::vec3 position_vox);
  /// Moves the proxy toward the device; returns where it ends up.
  const ProxyState& update(const PatchSnapshot& field, glm::vec3 device_vox);

  const ProxyState& state() const { return state_; }
  const SphereProxyOptions& options() const { return options_; }
  void set_friction(const CoulombFriction& friction) { options_.friction = friction; }

 private:
  // phi - r at p, and the unit gradient there.
  float clearance(const PatchSnapshot& field, glm::vec3 p, glm::vec3* normal) const;
  // p pulled onto phi - r = skin along the gradient.
  glm::vec3 onto_surface(const PatchSnapshot& field, glm::vec3 p) const;
  // The first point from `from` toward `to` whose clearance is below skin,
  // found by sphere tracing; `to` when there is none.
  glm::vec3 trace(const PatchSnapshot& field, glm::vec3 from, glm::vec3 to, bool* blocked) const;

  SphereProxyOptions options_;
  ProxyState state_;
  bool placed_ = false;
};

}  // namespace sculpt::core
