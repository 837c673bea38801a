#include "sculpt/core/haptics/haptic_renderer.h"

namespace sculpt::core {

HapticRenderer::HapticRenderer(const HapticSettings& settings)
    : settings_(settings),
      proxy_(settings.proxy),
      coupling_(settings.coupling),
      observer_(settings.passivity_max_damping_ns_per_m) {}

const HapticTick& HapticRenderer::tick(const PatchSnapshot& field, glm::vec3 device_vox,
                                       double t_s) {
  const double dt_s = started_ ? t_s - last_.t_s : 0.0;
  // Finite differences of the positions given: deterministic for a replay.
  glm::vec3 velocity_m_per_s(0.0f);
  if (started_ && dt_s > 0.0)
    velocity_m_per_s =
        (device_vox - last_.device_vox) * float(double(settings_.coupling.voxel_mm) * 1e-3 / dt_s);
  if (!started_) proxy_.reset(field, device_vox);
  const ProxyState& proxy = proxy_.update(field, device_vox);
  glm::vec3 force = coupling_.force(proxy.position_vox, device_vox, proxy.contact, proxy.normal,
                                    velocity_m_per_s);
  float damping = 0.0f;
  if (!proxy.contact) {
    observer_.reset();
  } else if (settings_.passivity_max_damping_ns_per_m > 0.0f) {
    force = observer_.apply(force, velocity_m_per_s, dt_s);
    damping = observer_.last_damping_ns_per_m();
  }
  last_.t_s = t_s;
  last_.device_vox = device_vox;
  last_.proxy = proxy;
  last_.force_n = force;
  last_.passivity_damping_ns_per_m = damping;
  started_ = true;
  return last_;
}

}  // namespace sculpt::core
