#pragma once
// OpenVDB files (.vdb), for the film and game tools (Blender, Houdini) and
// OpenVDB's own. Written: a FloatGrid "density", a fog volume holding
// density / 255 (0 empty .. 1 full, background 0), and, when there is a
// surface, a FloatGrid "surface", a narrow-band level set (GRID_LEVEL_SET,
// signed distance in voxel units, negative inside, active within
// kVdbHalfWidth voxels of the surface, background +-kVdbHalfWidth). Both
// have voxel size 1 and no translation, so voxel (x, y, z) sits at world
// (x, y, z) as in the exported meshes, and carry `sculpt_dims` (vec3i) so
// empty borders survive; a tool's pivot is `sculpt_pivot` (vec3s).
//
// Reading takes "density" (exactly: round(value * 255), so a file we wrote
// gives its density back bit for bit), else "surface" or the first float
// level set. Refused, with one message naming the file and the fault: a file
// OpenVDB cannot read, a chosen grid that is not float, no usable grid, a
// grid larger than VdbLimits, a transform that is not a uniform scale plus a
// translation, values that are not finite numbers.
//
// This header and vdb_file.cpp are the only place OpenVDB is seen: its
// headers take a long time to compile (docs/design.md).

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>

#include <glm/vec3.hpp>

#include "sculpt/base/result.h"
#include "sculpt/core/grid/dense_grid.h"

namespace sculpt::core {

/// Half width of the written level set's narrow band, voxels (OpenVDB's default).
inline constexpr float kVdbHalfWidth = 3.0f;

struct VdbLimits {
  /// Largest voxel count of the grid read (its active bounding box or its
  /// sculpt_dims): the volume limit, 2^32.
  int64_t max_voxels = int64_t{1} << 32;
  /// Longest edge, voxels.
  int max_edge = 1 << 16;
  /// Address space of the child process that parses the file with OpenVDB
  /// (RLIMIT_AS; not set in sanitizer builds, whose shadow memory needs
  /// terabytes). A damaged file whose lengths ask for more is refused (std::
  /// bad_alloc in the child) instead of taking the machine's memory. 4 GiB:
  /// the most one length OpenVDB reads (uint32) can claim, so with the
  /// program mapped beside it no such claim is granted; and OpenVDB's tree of a fully dense 512^3
  /// float grid is 0.5 GiB (a file needing more than 4 GiB of tree is refused
  /// as asking for too much memory). The dense result is streamed out in
  /// 1 MiB chunks, so it does not count against this.
  int64_t reader_address_space = int64_t{4} << 30;
  /// CPU seconds the child may spend (RLIMIT_CPU): a crafted file can keep
  /// OpenVDB's parser busy for many minutes (the fuzzer found one: 14 minutes
  /// under ASan); it is stopped and refused. A 512^3 grid parses in about one.
  int reader_cpu_seconds = 30;
  /// The child's stderr goes to /dev/null, so that a crash inside OpenVDB
  /// (glibc's "malloc(): corrupted top size", a sanitizer's report) leaves
  /// only the parent's one error line. False to see what it said.
  bool reader_stderr_to_null = true;
};

/// What write_vdb() writes; a null grid is left out (at least one is needed).
struct VdbGridsOut {
  const DenseGrid<uint8_t>* density = nullptr;
  /// Signed distance, voxel units, negative inside; same dims as density when both.
  const DenseGrid<float>* surface = nullptr;
  std::optional<glm::vec3> pivot;
};

/// What read_vdb() found: density when the file has a "density" grid, else
/// the level set as a signed distance in voxel units (outside the band
/// +-kVdbHalfWidth times the file's voxel size, in voxels).
struct VdbGridsIn {
  std::optional<DenseGrid<uint8_t>> density;
  std::optional<DenseGrid<float>> surface;
  std::optional<glm::vec3> pivot;
  /// The grid read ("density", "surface", ...).
  std::string grid_name;
};

/// Whether `path` names a .vdb file (by its extension, any case).
bool is_vdb_path(const std::filesystem::path& path);

/// Writes the grids: all of the file, or nothing (AtomicFileWriter).
Status write_vdb(const std::filesystem::path& path, const VdbGridsOut& grids);

/// Reads a .vdb file; errors name `path`. OpenVDB parses it in a child
/// process (fork): a file that crashes OpenVDB, or a child that dies, is an
/// error line ("OpenVDB could not read it (crashed: signal 6)"), and what the
/// child sends back is checked against `limits` before it is allocated.
Result<VdbGridsIn> read_vdb(const std::filesystem::path& path, const VdbLimits& limits = {});
/// The same from a stream (the fuzz target; the child reads it); errors name `name`.
Result<VdbGridsIn> read_vdb(std::istream& in, const std::string& name,
                            const VdbLimits& limits = {});

}  // namespace sculpt::core
