#pragma once
// One haptic tick for a sphere tool (DESIGN.md §5a): device position -> proxy
// on the patch -> force. The same code runs in the 1 kHz loop, in replays (in
// the recorded virtual time) and behind `sculpt haptics trace`, so a trace is
// what a device would have felt, bit for bit.
//
// Per tick: the proxy moves (sphere_proxy.h, with friction), the virtual
// coupling gives the force (virtual_coupling.h), the passivity observer adds
// damping only when the contact would give back more energy than it took
// (passivity_observer.h). No allocation, no lock, no brick decoded.

#include <glm/vec3.hpp>

#include "sculpt/core/haptics/passivity_observer.h"
#include "sculpt/core/haptics/patch_snapshot.h"
#include "sculpt/core/haptics/sphere_proxy.h"
#include "sculpt/core/haptics/virtual_coupling.h"

namespace sculpt::core {

struct HapticSettings {
  SphereProxyOptions proxy;
  CouplingOptions coupling;
  /// Upper bound of the damping the passivity controller may add (N·s/m);
  /// 0 turns the observer off.
  float passivity_max_damping_ns_per_m = 20.0f;
};

struct HapticTick {
  double t_s = 0.0;
  glm::vec3 device_vox{0.0f};
  ProxyState proxy;
  /// Force on the hand, N.
  glm::vec3 force_n{0.0f};
  /// Damping the passivity controller added this tick, N·s/m.
  float passivity_damping_ns_per_m = 0.0f;
};

class HapticRenderer {
 public:
  explicit HapticRenderer(const HapticSettings& settings = {});

  /// Runs one tick at time `t_s` (seconds, increasing) with the device at
  /// `device_vox` (material voxels).
  const HapticTick& tick(const PatchSnapshot& field, glm::vec3 device_vox, double t_s);

  const HapticTick& last() const { return last_; }
  const HapticSettings& settings() const { return settings_; }
  /// The energy the hand has put into the current contact, J: the passivity
  /// observer's sum after its damping, which keeps it from going below zero.
  double passivity_energy_j() const { return observer_.energy_j(); }

 private:
  HapticSettings settings_;
  SphereProxy proxy_;
  VirtualCoupling coupling_;
  PassivityObserver observer_;
  HapticTick last_;
  bool started_ = false;
};

}  // namespace sculpt::core
