// The force limits table. The Falcon's figures are the ones DESIGN.md §5a
// gives: a force it holds (Novint quotes about 9 N peak), a spring and a
// damper it renders without buzzing at 1 kHz, and a reach of 40 mm from the
// centre of its roughly 10 cm workspace.

#include "sculpt/hal/force/force_limits.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace sculpt::hal {
namespace {

constexpr ForceLimits force3(uint16_t vid, uint16_t pid, std::string_view name, float max_force_n,
                             float max_stiffness_n_per_mm, float max_damping_ns_per_m,
                             float workspace_radius_mm) {
  ForceLimits l;
  l.vendor_id = vid;
  l.product_id = pid;
  l.name = name;
  l.capability = ForceCapability::kForce3;
  l.max_force_n = max_force_n;
  l.max_stiffness_n_per_mm = max_stiffness_n_per_mm;
  l.max_damping_ns_per_m = max_damping_ns_per_m;
  l.workspace_radius_mm = workspace_radius_mm;
  return l;
}

// Sorted by vendor, product (find_force_limits searches it).
constexpr std::array kLimits = {
    // The simulated arm (hal/force/sim_arm.h) has a Falcon's figures, so CI's
    // closed loop runs at the limits a user's Falcon will.
    force3(0x0000, 0x0001, "Simulated arm", 8.0f, 3.0f, 20.0f, 40.0f),
    // The Falcon enumerates as its FTDI USB-serial chip with Novint's product id.
    force3(0x0403, 0xcb48, "Novint Falcon", 8.0f, 3.0f, 20.0f, 40.0f),
};

constexpr bool sorted() {
  for (size_t i = 1; i < kLimits.size(); ++i) {
    const auto& a = kLimits[i - 1];
    const auto& b = kLimits[i];
    if (a.vendor_id > b.vendor_id || (a.vendor_id == b.vendor_id && a.product_id >= b.product_id))
      return false;
  }
  return true;
}
static_assert(sorted(), "kLimits must be sorted by vendor:product");

// A setting that is NaN or negative is no setting: 0.
float clamp_setting(float value, float limit) {
  return std::isfinite(value) && value > 0.0f ? std::min(value, limit) : 0.0f;
}

}  // namespace

float ForceLimits::clamp_stiffness(float n_per_mm) const {
  return clamp_setting(n_per_mm, max_stiffness_n_per_mm);
}

float ForceLimits::clamp_damping(float ns_per_m) const {
  return clamp_setting(ns_per_m, max_damping_ns_per_m);
}

const ForceLimits* find_force_limits(uint16_t vendor_id, uint16_t product_id) {
  const auto it = std::lower_bound(kLimits.begin(), kLimits.end(), std::pair{vendor_id, product_id},
                                   [](const ForceLimits& l, std::pair<uint16_t, uint16_t> key) {
                                     return std::pair{l.vendor_id, l.product_id} < key;
                                   });
  if (it == kLimits.end() || it->vendor_id != vendor_id || it->product_id != product_id)
    return nullptr;
  return &*it;
}

std::span<const ForceLimits> all_force_limits() {
  return kLimits;
}

const ForceLimits& sim_arm_limits() {
  return kLimits[0];
}

}  // namespace sculpt::hal
