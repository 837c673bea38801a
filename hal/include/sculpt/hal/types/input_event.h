#pragma once
// What the parsers produce and the main loop consumes: motion samples,
// buttons, battery levels and connect/disconnect events, in the station's
// device frame (DESIGN.md §3: right-handed, +X right, +Y up, +Z toward the
// user; each axis in [-1, 1]).

#include <array>
#include <cstdint>

#include "sculpt/hal/types/tracker_pose.h"

namespace sculpt::hal {

enum class InputKind : uint8_t {
  kMotion,        ///< axes holds one full sample
  kButton,        ///< button, pressed
  kBattery,       ///< battery_percent, charging
  kConnected,     ///< device_id appeared (first event of every reader)
  kDisconnected,  ///< device_id is gone (last event of every reader)
  /// A tracker lost sight of its target: the stroke ends, and the next pose
  /// re-anchors instead of jumping.
  kTrackingLost,
};

/// Axis indices in InputEvent::axes.
enum Axis : int { kTx = 0, kTy, kTz, kRx, kRy, kRz, kAxisCount };

struct InputEvent {
  InputKind kind = InputKind::kMotion;
  uint32_t device_id = 0;
  int64_t t_ns = 0;  ///< time of the report that completed this event, monotonic ns
  /// When its reader read that report, monotonic ns on this machine: t_ns
  /// for a device read now, but a played session's t_ns is the recording's
  /// clock. Latencies count from it; 0 when unknown (not from a reader).
  int64_t arrived_ns = 0;
  /// kMotion: tx ty tz rx ry rz in [-1, 1]. Translation is a deflection (3D
  /// mouse) or a position in the device's range (absolute devices); rotation
  /// likewise, as a fraction of full twist.
  std::array<float, kAxisCount> axes{};
  bool absolute = false;  ///< kMotion: position-control device (tracker, absolute HID axes)
  /// kMotion from a tracker: `pose` holds the absolute pose in the tracker's
  /// frame (mm, unit quaternion w x y z) and `axes` are unused. Set with
  /// `absolute`.
  bool has_pose = false;
  TrackerPose pose;
  bool translation_stale = false;  ///< kMotion: translation half not refreshed by this sample
  bool rotation_stale = false;     ///< kMotion: rotation half not refreshed by this sample
  /// kMotion, relative: each axis integrated over time since the device
  /// connected, in axis-seconds (DeflectionIntegral fills it). The pose
  /// integrator uses differences of it, so skipping samples (newest wins)
  /// loses no motion.
  std::array<double, kAxisCount> integral{};
  int button = 0;  ///< kButton: logical button from 0
  bool pressed = false;
  int battery_percent = 0;  ///< kBattery: 0..100
  bool charging = false;
};

}  // namespace sculpt::hal
