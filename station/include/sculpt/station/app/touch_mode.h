#pragma once
// Touch mode (DESIGN.md §5a) for devices with no force output, a 3D mouse
// above all: the contact a force device gets, without the force. The device
// moves a point; the tool is a sphere proxy (core/haptics/sphere_proxy.h)
// that follows it until it meets the material, then rests on it and slides
// along it, however hard the cap is pushed. The push is the cap's deflection
// into the material, scaled to newtons (full deflection: full_push_n), so
// with the button held the tool carves (or adds) only where the cap is pushed
// past the press threshold, deeper the harder (core/haptics/press_dab.h).
//
// A pure function of the events and the volume: replays reproduce it.
// Thread safety: the station loop's thread.

#include <memory>

#include <glm/vec3.hpp>

#include "sculpt/core/haptics/patch_keeper.h"
#include "sculpt/core/haptics/press_dab.h"
#include "sculpt/core/haptics/sphere_proxy.h"
#include "sculpt/core/volume/volume.h"

namespace sculpt::station {

struct TouchOptions {
  /// The push at full deflection of the cap, N.
  float full_push_n = 4.0f;
  core::PressOptions press;
};

struct TouchResult {
  /// Where the proxy rests (or follows the device in free air), voxels.
  glm::vec3 proxy_vox{0.0f};
  /// Where a dab goes: the proxy pressed in along the normal (when pushed
  /// past the threshold), else the proxy.
  glm::vec3 tool_vox{0.0f};
  bool contact = false;
  /// Pushed past the press threshold.
  bool pressing_in = false;
  /// The push along the normal, N.
  float push_n = 0.0f;
};

class TouchMode {
 public:
  explicit TouchMode(const TouchOptions& options = {});

  /// Moves the proxy of radius `radius_vox` toward `device_vox` on `volume`
  /// (whose `generation` moves on when it is replaced). `deflection`: how
  /// far the cap is pushed, in [0, 1] (0 for a device without one).
  const TouchResult& update(const core::Volume& volume, uint64_t generation, glm::vec3 device_vox,
                            float deflection, float radius_vox);
  /// Forgets the proxy: the next update starts it at the device.
  void reset();
  const TouchResult& last() const { return last_; }

 private:
  TouchOptions options_;
  std::unique_ptr<core::PatchKeeper> keeper_;
  std::unique_ptr<core::SphereProxy> proxy_;
  float radius_vox_ = -1.0f;
  int levels_ = -1;
  TouchResult last_;
};

}  // namespace sculpt::station
