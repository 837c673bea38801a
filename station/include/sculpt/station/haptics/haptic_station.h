#pragma once
// A force device at the station (DESIGN.md §5a): its haptic loop on its own
// thread at 1 kHz, the contact law between it and the material, and the
// sculpting thread's half: the distance patch kept around the proxy, and the
// station's tool moved to where the device presses.
//
//   haptic thread (1 kHz)    device -> ContactForceLaw -> safety -> device
//        ^ patch (PatchExchange)          | contact records (ring)
//        |                                v
//   sculpting thread (poll)  PatchKeeper <- proxy;  proxy -> pointer commands
//
// The tool follows the proxy, so it rests on the sculpture instead of
// sinking in. Button 1 switches between add and subtract (as on a 3D
// mouse). Button 0 held carves (or adds) only where the device pushes
// beyond the press threshold (core/haptics/press_dab.h): resting the tool
// on the clay carves nothing, pushing harder carves deeper and the material
// resists. In free air the button sculpts at the tool, as with any device.
// The tool's moves and presses are pointer commands of the station, so a
// recording replays the sculpture bit for bit.
//
// While the station records, the loop goes into the session too
// (haptic_recording.h): its set-up, every patch published and every tick,
// so a replay runs it again. Starting a recording restarts the loop, so the
// session holds it from its first tick; the force ramps in again.
//
// The proxy is a sphere of the tool's size (half its largest extent for
// shapes other than the sphere); a tool change restarts the loop with the
// new radius, and the force ramps in again.
//
// Thread safety: start(), stop(), sculpting_side(), contact() and figures()
// from the sculpting side (under the hub's mutex, or one thread); enable(),
// drop() and set_clutch() from any thread.

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include <glm/vec3.hpp>

#include "sculpt/core/haptics/patch_exchange.h"
#include "sculpt/core/haptics/patch_keeper.h"
#include "sculpt/core/haptics/press_dab.h"
#include "sculpt/hal/force/force_device.h"
#include "sculpt/hal/haptics/haptic_loop.h"
#include "sculpt/hal/haptics/haptic_thread.h"
#include "sculpt/station/app/input_hub.h"
#include "sculpt/station/haptics/contact_force_law.h"
#include "sculpt/station/haptics/haptic_recording.h"

namespace sculpt::station {

struct HapticStationOptions {
  /// The contact; its proxy radius follows the tool.
  ContactSettings contact;
  core::PressOptions press;
  hal::HapticLoopOptions loop;
  hal::HapticThreadOptions thread;
  /// False: the device only feels the material and moves no tool (while a
  /// session plays the tool, say).
  bool drives_tool = true;
  /// Force on from the start (it ramps in); else after enable().
  bool enabled = true;
};

/// What the panel and `--stats` show.
struct HapticFigures {
  std::string device;
  bool running = false;
  int64_t ticks = 0;
  int64_t late_ticks = 0;  ///< period over 1.5 ms
  int64_t skipped_deadlines = 0;
  int threads = 0;              ///< ticking threads: 2 with the standby twin
  int64_t standby_rescues = 0;  ///< ticks run on time while the other thread woke late
  int64_t device_faults = 0;
  int64_t watchdog_trips = 0;
  int64_t records_dropped = 0;
  double worst_period_us = 0.0;
  /// Percentiles of the period, us; from the loop's own histogram, so only
  /// once it has stopped (0 while running).
  double period_p50_us = 0.0;
  double period_p99_us = 0.0;
  float max_force_n = 0.0f;
  float ramp = 0.0f;
  bool realtime = false;
  std::string realtime_note;
  core::PatchKeeperFigures patch;
  int64_t restarts = 0;  ///< loop restarts for a new tool
};

class HapticStation final : public PollListener {
 public:
  HapticStation(std::unique_ptr<hal::ForceDevice> device, const HapticStationOptions& options);
  ~HapticStation() override;
  HapticStation(const HapticStation&) = delete;
  HapticStation& operator=(const HapticStation&) = delete;

  /// Starts the loop with the tool at `start_vox` when the device is at its
  /// origin, and a proxy of `radius_vox`.
  void start(glm::vec3 start_vox, float radius_vox);
  /// Stops the loop; the device is left with zero force.
  void stop();
  bool running() const { return thread_ != nullptr && thread_->running(); }
  /// The device went away (unplugged, or the simulated arm's script ended
  /// with an unplug); any thread.
  bool device_gone() const { return gone_.load(std::memory_order_acquire); }

  /// The sculpting side, every poll: takes the loop's newest contact, moves
  /// the controller's tool to it (and presses), keeps the patch current.
  void sculpting_side(StationController& controller, int64_t now_ns);
  /// The hub's poll: sculpting_side().
  void on_poll(StationController& controller, int64_t now_ns) override {
    sculpting_side(controller, now_ns);
  }

  void enable();
  void drop();
  bool enabled() const { return enabled_.load(); }
  void set_clutch(bool held);
  /// New contact settings (the panel): the loop restarts with them, the
  /// tool staying where it is, and the force ramps in again.
  void set_contact(const ContactSettings& contact);
  /// The settings in force (clamped to the device).
  ContactSettings contact_settings() const;

  /// The newest contact the sculpting side took.
  const ContactRecord& contact() const { return contact_; }
  /// The newest tick (position in mm, buttons, force written).
  const hal::HapticTickRecord& tick() const { return tick_; }
  HapticFigures figures() const;
  const hal::ForceDevice& device() const { return *device_; }

 private:
  // Makes the loop (not started) with the tool at start_vox at the device's origin.
  void start_loop(glm::vec3 start_vox, float radius_vox);
  void stop_loop();
  // A new loop with a proxy of radius_vox, the tool where it is.
  void restart(float radius_vox);
  void drive_tool(StationController& controller, int64_t now_ns);

  std::unique_ptr<hal::ForceDevice> device_;
  HapticStationOptions options_;
  std::unique_ptr<core::PatchExchange> exchange_;
  std::unique_ptr<core::PatchKeeper> keeper_;
  std::unique_ptr<ContactForceLaw> law_;
  std::unique_ptr<hal::HapticLoop> loop_;
  std::unique_ptr<hal::HapticThread> thread_;
  // Figures of loops stopped for a new tool, added to the running one's.
  HapticFigures past_;
  ContactRecord contact_;
  hal::HapticTickRecord tick_;
  bool have_contact_ = false;
  // The running loop's set-up, and whether the recording has it.
  HapticLoopSetup setup_;
  bool setup_recorded_ = false;
  bool recording_ = false;
  uint64_t tool_version_ = 0;
  bool tool_seen_ = false;
  bool pressing_ = false;
  bool mode_button_ = false;
  // Presses of the mode button among the ticks popped but not yet acted on:
  // a click shorter than the gap between two polls (a slow frame) is still
  // a click, though the newest tick no longer holds it.
  int mode_presses_ = 0;
  float proxy_radius_vox_ = 0.0f;  // full-resolution voxels
  int volume_levels_ = 5;          // of the volume the patch is read from
  glm::vec3 last_tool_vox_{-1e9f};
  // The user's intent, kept across loop restarts.
  std::atomic<bool> enabled_{false};
  std::atomic<bool> clutch_{false};
  std::atomic<bool> gone_{false};
};

}  // namespace sculpt::station
