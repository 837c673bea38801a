#pragma once
// The force a device feels from the material (DESIGN.md §5a): the station's
// hal::ForceLaw, run by the haptic loop at 1 kHz. It maps the device's
// position into the material (workspace scale and clutch), moves the sphere
// proxy on the newest distance patch the sculpting side published
// (core::PatchExchange), and returns the coupling's force in the device's
// frame.
//
// The mapping: tool_vox = device_mm * workspace_scale / voxel_mm + offset_vox.
// A small device (the Falcon's 40 mm) reaches a whole sculpture with a scale
// above 1, or by the clutch: while it is held, the device moves and the tool
// stays (offset_vox follows), and no force is felt. The coupling then works in
// device millimetres (its voxel size is voxel_mm / workspace_scale), so the
// stiffness set is the stiffness the hand feels, whatever the scale, and the
// device's limits bound it.
//
// Thread safety: force_n() on the haptic thread only. set_clutch() from any
// thread. contacts() is a single-consumer ring for the sculpting side.

#include <atomic>
#include <cstdint>

#include <glm/vec3.hpp>

#include "sculpt/core/haptics/haptic_renderer.h"
#include "sculpt/core/haptics/patch_exchange.h"
#include "sculpt/hal/force/force_limits.h"
#include "sculpt/hal/haptics/haptic_loop.h"
#include "sculpt/hal/input/spsc_ring.h"

namespace sculpt::station {

/// The contact's defaults: the core's, with 10 N·s/m of damping along the
/// contact normal. A spring sampled every T with a tick of delay loses about
/// k (T/2 + T) of damping (the hold's half tick, Colgate & Schenkel's
/// passivity bound, plus the delay): 4.5 N·s/m for the Falcon's 3 N/mm at
/// 1 kHz. Without more, a press on the stiffest wall rings at about 33 Hz for
/// most of a second; with it, it rests within 0.1 s
/// (tests/station/haptics/contact_force_law_test.cpp shows both).
inline core::HapticSettings default_contact_haptics() {
  core::HapticSettings s;
  s.coupling.damping_ns_per_m = 10.0f;
  return s;
}

struct ContactSettings {
  /// The proxy, coupling and passivity settings; stiffness and damping are
  /// clamped to the device's limits, voxel_mm is replaced (see the header).
  core::HapticSettings haptic = default_contact_haptics();
  /// Material millimetres per device millimetre.
  float workspace_scale = 1.0f;
  /// The material's voxel size, mm.
  float voxel_mm = 0.5f;
  /// Multiplies the force felt (0..1 softens everything at once).
  float force_scale = 1.0f;
  /// Device buttons that act as the clutch while held.
  uint32_t clutch_buttons = 0;
  /// The level of the wavelet pyramid the patch is sampled at (0: full
  /// resolution). A big tool's proxy needs the distance accurate as far out
  /// as its radius, and a patch's cost grows with the cube of that band;
  /// at level k the band is 2^k times narrower in the patch's voxels. The
  /// proxy radius is in full-resolution voxels whatever the level.
  int patch_level = 0;
};

/// One tick of contact, for the window (the device point, the proxy, the
/// force arrow) and the sculpting side.
struct ContactRecord {
  int64_t t_ns = 0;
  glm::vec3 device_vox{0.0f};
  glm::vec3 proxy_vox{0.0f};
  bool contact = false;
  /// Outward normal of the material at the proxy (in contact).
  glm::vec3 normal{0.0f};
  bool clutched = false;
  /// The force on the hand, N, device frame (before the loop's safety rules).
  glm::vec3 force_n{0.0f};
};

class ContactForceLaw final : public hal::ForceLaw {
 public:
  /// `start_vox`: where the tool is when the device is at its origin.
  ContactForceLaw(core::PatchExchange& patches, const hal::ForceLimits& limits,
                  const ContactSettings& settings, glm::vec3 start_vox);

  glm::vec3 force_n(const hal::HapticInput& input) override;
  /// The patch's version the last force_n() read, times two, plus one when
  /// the clutch key was held (law_inputs() below takes it apart).
  uint64_t inputs() const override { return inputs_; }

  /// Maps the device at `device_mm` to the tool at `tool_vox` (before the
  /// loop runs: a restart keeps the tool where it was).
  void place_tool(glm::vec3 tool_vox, glm::vec3 device_mm) {
    offset_vox_ = tool_vox - device_mm * vox_per_device_mm_;
    tool_vox_ = tool_vox;
  }
  /// Holds or releases the clutch (a key), from any thread.
  void set_clutch(bool held) { clutch_key_.store(held, std::memory_order_relaxed); }

  /// The settings in force (after clamping to the device).
  const ContactSettings& settings() const { return settings_; }
  const core::HapticRenderer& renderer() const { return renderer_; }
  /// What each tick did, oldest first; full means the consumer is behind and
  /// records are dropped (counted in records_dropped()).
  hal::SpscRing<ContactRecord>& contacts() { return contacts_; }
  int64_t records_dropped() const { return dropped_.load(std::memory_order_relaxed); }

 private:
  core::PatchExchange& patches_;
  ContactSettings settings_;
  core::HapticRenderer renderer_;
  float vox_per_device_mm_;
  glm::vec3 offset_vox_;
  glm::vec3 tool_vox_;
  std::atomic<bool> clutch_key_{false};
  hal::SpscRing<ContactRecord> contacts_;
  std::atomic<int64_t> dropped_{0};
  uint64_t inputs_ = 0;
};

/// What ContactForceLaw::inputs() packs: the patch version read and the
/// clutch key.
struct ContactLawInputs {
  uint64_t patch_version = 0;
  bool clutch_key = false;
};
inline ContactLawInputs law_inputs(uint64_t packed) {
  return {packed >> 1, (packed & 1u) != 0};
}

}  // namespace sculpt::station
