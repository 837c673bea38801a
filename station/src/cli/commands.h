#pragma once
// The `sculpt` subcommands (DESIGN.md §7). Each add_*_command registers its
// options on `app` and, when the user picks it, sets `action` to the function
// that runs it and returns the exit code: 0 success, 1 bad input (one line on
// stderr naming the input), 2 usage error (CLI11 reports those).

#include <functional>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/field_options.h"
#include "cli/mesh_export_options.h"
#include "sculpt/base/result.h"

namespace sculpt::station::cli {

using Action = std::function<int()>;

void add_wavelet_command(CLI::App& app, Action& action);
void add_run_command(CLI::App& app, Action& action);
void add_bench_command(CLI::App& app, Action& action);
void add_devices_command(CLI::App& app, Action& action);
void add_mesh_command(CLI::App& app, Action& action);
void add_rotate_command(CLI::App& app, Action& action);
void add_stamp_command(CLI::App& app, Action& action);
void add_replay_command(CLI::App& app, Action& action);
void add_session_command(CLI::App& app, Action& action);
void add_record_command(CLI::App& app, Action& action);
void add_distance_command(CLI::App& app, Action& action);
void add_voxelize_command(CLI::App& app, Action& action);
void add_close_command(CLI::App& app, Action& action);
void add_offset_command(CLI::App& app, Action& action);
void add_contours_command(CLI::App& app, Action& action);
void add_nurbs_command(CLI::App& app, Action& action);
void add_haptics_command(CLI::App& app, Action& action);
void add_export_command(CLI::App& app, Action& action);
void add_import_command(CLI::App& app, Action& action);

/// What `sculpt mesh` (and `sculpt export` to a mesh) reads, how it meshes
/// and what it writes.
struct MeshCliOptions {
  std::string input;   ///< a volume (.nrrd, .vdb), or a mesh to check or simplify
  std::string output;  ///< .ply, .obj, .stl or .glb; may be empty for a mesh --check
  float iso = 127.5f;  ///< density units
  int lod = 0;
  int threads = 0;
  DensityOptions density;
  MeshExportOptions mesh;
};
/// Meshes the volume (or passes the mesh read in on) and writes it; returns
/// the exit code.
int mesh_to_output(const MeshCliOptions& options);

/// What `sculpt voxelize` (and `sculpt import` of a mesh) reads and writes.
struct VoxelizeCliOptions {
  std::string input, output;
  int size = 0;         ///< grid edge N; 0: from voxel_mm
  double voxel_mm = 0;  ///< voxel edge in mm when size is 0 (the mesh's scale kept)
  double unit_mm = 0;   ///< mm per mesh unit; 0: 1000 for .glb (glTF is metres), else 1
  float margin = 4.0f;  ///< voxels between the mesh and the grid's faces
  bool sdf = false;     ///< float32 signed distance instead of uint8 density
  int threads = 0;
};
/// Voxelizes the closed mesh and writes the volume; returns the exit code.
int voxelize_to_output(const VoxelizeCliOptions& options);
/// Registers --size, --voxel-mm, --unit-mm, --margin, --sdf and --threads.
void add_voxelize_grid_options(CLI::App* command, VoxelizeCliOptions& options);

/// What `sculpt replay` (and the main job, which replays the demo) computes
/// and writes; an empty path means "do not write it".
struct ReplayCliOptions {
  std::string session;
  bool fast = false;
  double speed = 1.0;
  int threads = 0;
  std::string volume, mesh, png, stats, samples;
  std::string forces;               ///< the force device's ticks run again (JSON Lines)
  std::string renderer = "auto";    ///< for png: auto, gl or software
  std::string normals = "density";  ///< mesh and png normals: density or distance (gradient)
  std::string project;              ///< write the final state as a project file
  MeshExportOptions mesh_export;    ///< --simplify, --max-error, --check of the mesh
};
/// Replays and writes the outputs asked for; returns the exit code.
int replay_to_outputs(const ReplayCliOptions& options);

/// Prints "sculpt: <message>" on stderr and returns exit code 1.
int report(const Error& error);

}  // namespace sculpt::station::cli
