#include "sculpt/station/app/touch_mode.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace sculpt::station {

TouchMode::TouchMode(const TouchOptions& options) : options_(options) {}

void TouchMode::reset() {
  keeper_.reset();
  proxy_.reset();
  radius_vox_ = -1.0f;
}

const TouchResult& TouchMode::update(const core::Volume& volume, uint64_t generation,
                                     glm::vec3 device_vox, float deflection, float radius_vox) {
  // A new tool size (or volume of other levels): a new proxy of its size.
  if (!keeper_ || radius_vox != radius_vox_ || volume.levels() != levels_) {
    const core::SpherePatch sphere = core::sphere_patch(radius_vox, volume.levels());
    keeper_ = std::make_unique<core::PatchKeeper>(sphere.options, sphere.level);
    core::SphereProxyOptions proxy;
    proxy.radius_vox = radius_vox / sphere.scale();
    proxy_ = std::make_unique<core::SphereProxy>(proxy);
    // Where the tool was stays where it is (the device point at the first update).
    const glm::vec3 from = radius_vox_ < 0.0f ? device_vox : last_.proxy_vox;
    keeper_->update(volume, generation, from);
    proxy_->reset(keeper_->patch().snapshot(), sphere.to_patch(from));
    radius_vox_ = radius_vox;
    levels_ = volume.levels();
    last_.proxy_vox = sphere.from_patch(proxy_->state().position_vox);
  }
  const core::SpherePatch mapping{keeper_->level(), {}};
  const glm::vec3 before = last_.proxy_vox;
  keeper_->update(volume, generation, before);
  const core::ProxyState& s =
      proxy_->update(keeper_->patch().snapshot(), mapping.to_patch(device_vox));
  last_.proxy_vox = mapping.from_patch(s.position_vox);
  last_.contact = s.contact;
  last_.tool_vox = last_.proxy_vox;
  last_.pressing_in = false;
  last_.push_n = 0.0f;
  if (s.contact) {
    // The share of the device's motion that went into the material.
    const glm::vec3 motion = device_vox - before;
    const float length = glm::length(motion);
    const float into = length > 1e-6f ? std::max(0.0f, -glm::dot(motion / length, s.normal)) : 0.0f;
    last_.push_n = options_.full_push_n * std::clamp(deflection, 0.0f, 1.0f) * into;
    if (const auto pressed = core::pressed_dab_position(
            last_.proxy_vox, s.normal, s.normal * last_.push_n, true, options_.press)) {
      last_.pressing_in = true;
      last_.tool_vox = *pressed;
    }
  }
  return last_;
}

}  // namespace sculpt::station
