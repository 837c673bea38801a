#include "sculpt/station/haptics/contact_force_law.h"

#include <algorithm>
#include <cmath>

#include "sculpt/core/haptics/patch_keeper.h"

namespace sculpt::station {
namespace {

constexpr size_t kContactRecords = 1024;

bool usable(float v) {
  return std::isfinite(v) && v > 0.0f;
}

// The settings the device can render: stiffness and damping within its
// limits, the coupling in device millimetres, its force cap the device's.
ContactSettings clamped(ContactSettings s, const hal::ForceLimits& limits) {
  if (!usable(s.workspace_scale)) s.workspace_scale = 1.0f;
  if (!usable(s.voxel_mm)) s.voxel_mm = 0.5f;
  s.force_scale = std::isfinite(s.force_scale) ? std::clamp(s.force_scale, 0.0f, 1.0f) : 0.0f;
  core::CouplingOptions& c = s.haptic.coupling;
  c.stiffness_n_per_mm = limits.clamp_stiffness(c.stiffness_n_per_mm);
  c.damping_ns_per_m = limits.clamp_damping(c.damping_ns_per_m);
  c.max_force_n = std::min(usable(c.max_force_n) ? c.max_force_n : 0.0f, limits.max_force_n);
  // The proxy works in the patch's voxels: 2^level full-resolution ones.
  s.patch_level = std::clamp(s.patch_level, 0, 8);
  const float scale = static_cast<float>(1 << s.patch_level);
  c.voxel_mm = s.voxel_mm * scale / s.workspace_scale;
  s.haptic.proxy.radius_vox /= scale;
  s.haptic.passivity_max_damping_ns_per_m =
      limits.clamp_damping(s.haptic.passivity_max_damping_ns_per_m);
  return s;
}

}  // namespace

ContactForceLaw::ContactForceLaw(core::PatchExchange& patches, const hal::ForceLimits& limits,
                                 const ContactSettings& settings, glm::vec3 start_vox)
    : patches_(patches),
      settings_(clamped(settings, limits)),
      renderer_(settings_.haptic),
      vox_per_device_mm_(settings_.workspace_scale / settings_.voxel_mm),
      offset_vox_(start_vox),
      tool_vox_(start_vox),
      contacts_(kContactRecords) {}

glm::vec3 ContactForceLaw::force_n(const hal::HapticInput& input) {
  const bool clutch_key = clutch_key_.load(std::memory_order_relaxed);
  const bool clutched = clutch_key || (input.device.buttons & settings_.clutch_buttons) != 0;
  const glm::vec3 mapped_vox = input.device.position_mm * vox_per_device_mm_;
  // While clutched the tool stays where it is: the offset absorbs the motion.
  if (clutched) offset_vox_ = tool_vox_ - mapped_vox;
  tool_vox_ = mapped_vox + offset_vox_;

  ContactRecord record;
  record.t_ns = input.t_ns;
  record.device_vox = tool_vox_;
  record.proxy_vox = tool_vox_;
  record.clutched = clutched;
  const core::PatchSnapshot& patch = patches_.acquire();
  inputs_ = (patch.version << 1) | (clutch_key ? 1u : 0u);
  if (!patch.empty() && !clutched) {
    const core::SpherePatch mapping{settings_.patch_level, {}};
    const core::HapticTick& tick =
        renderer_.tick(patch, mapping.to_patch(tool_vox_), static_cast<double>(input.t_ns) * 1e-9);
    record.proxy_vox = mapping.from_patch(tick.proxy.position_vox);
    record.contact = tick.proxy.contact;
    record.normal = tick.proxy.normal;
    record.force_n = tick.force_n * settings_.force_scale;
  }
  if (!contacts_.try_push(record)) dropped_.fetch_add(1, std::memory_order_relaxed);
  return record.force_n;
}

}  // namespace sculpt::station
