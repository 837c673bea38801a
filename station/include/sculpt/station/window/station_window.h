#pragma once
// The live station: a GLFW window with the GL renderer and the ImGui panel,
// fed by the device readers (or, with no device, by the demo session played
// as a live device) and by the ordinary mouse and keyboard.
//
// Per frame: drain the readers' rings, integrate the pose, sample dabs,
// sculpt, re-mesh dirty bricks, upload what changed, draw. Reading never
// waits for sculpting: each device has its own reader thread, and a slow
// frame only means the next frame integrates more motion (nothing is lost).

#include <string>

#include "sculpt/hal/pose/tracker_mapping.h"
#include "sculpt/station/view/surface_mesher.h"

namespace sculpt::station {

struct WindowOptions {
  /// auto (a device if one is attached, else the demo session), sim:FILE,
  /// a device id as `sculpt devices` prints it, or a tracker
  /// (opentrack[:PORT], vrpn:NAME@HOST[:PORT]).
  std::string device = "auto";
  /// opentrack devices: the address to listen on (loopback: only this machine).
  std::string listen = "127.0.0.1";
  bool sim_loop = false;            ///< sim devices: play the session over and over (the soak)
  double sim_speed = 1.0;           ///< sim devices: play this much faster
  std::string project;              ///< open this project first
  std::string record;               ///< start recording to this session file
  std::string stats;                ///< write frame and latency figures here at exit (JSON)
  double stats_every_s = 0;         ///< and every this many seconds while running (0: never)
  std::string screenshot;           ///< PNG of the last frame, at exit
  int frames = 0;                   ///< stop after this many frames (0: when closed)
  bool exit_when_replayed = false;  ///< stop when the sim device's session ends
  int lod = -1;                     ///< a fixed level of detail for every brick (-1: automatic)
  bool distance_normals = false;    ///< shade with the distance field's gradient
  int undo_mib = 256;               ///< the undo history's memory budget
  int mesh_threads = 0;             ///< threads meshing the surface's changes (0: all cores)
  /// How far simplifying may move the drawn surface, in voxels of each
  /// brick's level (0: draw the marching-cubes meshes as they are).
  float simplify_error = SurfaceMesher::kSimplifyError;
  /// A force device (`sim-arm:HAND_SCRIPT`, ...): its haptic loop ticks at
  /// 1 kHz beside the window and the tool rests on the material (empty: none).
  /// While a sim device plays a session, the force device only feels.
  std::string haptic;
  std::string falcon_firmware;             ///< the Novint firmware file, for --haptic falcon
  float haptic_stiffness_n_per_mm = 1.0f;  ///< clamped to the device's limit
  float workspace_scale = 1.0f;            ///< material mm per device mm
  /// The haptic thread wakes this early and polls to each tick's deadline
  /// (hal::HapticThreadOptions::spin_ns), microseconds.
  int haptic_spin_us = 0;
  /// A standby twin of the haptic thread on another core
  /// (hal::HapticThreadOptions::standby).
  bool haptic_standby = true;
  float voxel_mm = 0.5f;  ///< the material's voxel size
  /// A tracker's scale and axes; recorded sessions carry it (a tracker
  /// command), so replays map the same way.
  hal::TrackerCalibration tracker;
  bool vsync = true;
  /// Dabs drawn by a stand-in before their mesh is ready (app/dab_stand_ins.h).
  bool stand_ins = true;
  bool visible = true;
  int width = 1280;
  int height = 800;
};

/// Runs the window until it is closed (or `frames` are drawn). Returns the
/// process exit code; errors (no display, a device that cannot be opened,
/// a project that does not open) are reported on stderr.
int run_window(const WindowOptions& options);

}  // namespace sculpt::station
