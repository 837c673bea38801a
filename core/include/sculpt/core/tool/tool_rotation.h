#pragma once
// Discrete rotation of a tool into a target grid ("Discrete tools for virtual
// sculpture" §3.1 and §3.2).
//
// A tool placed with rotation R (tool frame -> target frame, a proper rotation
// matrix) and its pivot at `position` (target voxel units, sub-voxel allowed)
// covers target voxel k with the tool sample at t = R^T (k - position) + pivot.
// The inverse method evaluates this map for every target voxel of the rotated
// tool's bounding box (§3.1.1: the box of the 8 rotated corners), so no target
// voxel is missed (§3.1.3). Nearest sampling takes the closest tool voxel;
// trilinear sampling (§3.2) blends its 8 neighbours. Outside the tool reads 0.
//
// The map is evaluated in 16.16 fixed point: the brute-force method multiplies
// every target position by the (fixed-point) inverse matrix, the incremental
// method (Algorithm 1) inverse-rotates the basis once and steps by it. Integer
// steps accumulate no rounding, so both methods produce identical voxels, with
// or without antialiasing. The positional error of the fixed-point map is
// below 2^-16 voxel per step (< 0.01 voxel across a 512-voxel box).
//
// Always rotate the reference tool, never an already rotated one (§3.1).

#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "sculpt/core/grid/box.h"
#include "sculpt/core/grid/dense_grid.h"
#include "sculpt/core/tool/tool.h"

namespace sculpt::core {

enum class Sampling { kNearest, kTrilinear };
enum class RotationMethod { kBrute, kIncremental };
/// What the incremental method may leave unsampled. kReachAndCore (the
/// default): rows are cut to the tool's reach ball and the core ball is
/// filled with the core value. kNone: every voxel of the rotated box is
/// sampled (lines still stop at the tool's grid, as brute force's bounds test
/// does), for measuring Algorithm 1 alone; same results, bit for bit.
enum class RotationClipping { kReachAndCore, kNone };

/// The rotation of Euler angles in degrees, extrinsic about x, then y, then z:
/// Rz * Ry * Rx, the matrix of scipy's Rotation.from_euler("xyz", deg, degrees=True).
glm::mat3 euler_xyz_deg(glm::vec3 degrees);

/// Allows (default) or forbids the AVX2 sampling kernel, which is used only
/// when the CPU has AVX2; returns whether it will be used. Results are the
/// same either way; tests compare the two paths. Affects all threads.
bool use_vector_kernel(bool enabled);

/// A reference tool made ready for fast sampling: a copy padded by two zero
/// voxels on every side (no bounds tests in the inner loop), and a table
/// marking the trilinear cells (a voxel and its +1 neighbours) whose 8
/// corners are equal: a sculpting tool is uniform inside and out, so most
/// trilinear samples cost one load. Build once per tool; immutable and
/// thread-safe afterwards.
///
/// The cell tables (10 bytes a cell) are built on the first call to cells()
/// or corners(), once, whichever thread asks: a ball brush sweeps its sphere
/// without rotating it and never asks, and for a 66-voxel ball they are 27 MB
/// of fresh pages: 71 ms of the sculpting thread replaying, 130 to 150 ms
/// live, at each change of size (docs/performance.md).
class PreparedTool {
 public:
  /// Padding of the sampling grid on every side, in voxels.
  static constexpr int kPad = 2;

  explicit PreparedTool(Tool tool);

  const Tool& tool() const { return tool_; }
  glm::ivec3 dims() const { return tool_.density.dims(); }
  glm::vec3 pivot() const { return tool_.pivot; }
  /// Largest distance from the pivot at which a sample can be non-zero
  /// (voxel units, trilinear support included).
  float reach_vox() const { return reach_vox_[1]; }
  /// The tool's core: every sample, nearest or trilinear, taken closer than
  /// core_radius_vox() to the pivot (voxel units; <= 0: no core) reads
  /// core_value() (255 inside a solid tool). Rotation fills it without sampling.
  float core_radius_vox() const { return core_radius_vox_[1]; }
  /// The same two radii for one sampling, as tight as it allows: a nearest
  /// sample reads the voxel within half a voxel of it on every axis, a
  /// trilinear one the corners within one voxel.
  float reach_vox(Sampling s) const { return reach_vox_[s == Sampling::kTrilinear]; }
  float core_radius_vox(Sampling s) const { return core_radius_vox_[s == Sampling::kTrilinear]; }
  uint8_t core_value() const { return core_value_; }

  // The kernels' view (RotationFrame): padded grid and cell table.
  glm::ivec3 padded_dims() const { return padded_dims_; }
  const uint8_t* padded() const { return padded_.data(); }
  /// Per cell: 0 when its corners differ, else 0x100 | their value.
  const uint16_t* cells() const {
    std::call_once(tables_built_, [this] { build_cell_tables(); });
    return cells_.get();
  }
  /// Per cell: its 8 corners, bytes (x, y, z), (x, y+1, z), (x+1, y, z),
  /// (x+1, y+1, z), then the same at z+1, from the lowest; the vector
  /// kernel's trilinear source (one load per sample).
  const uint64_t* corners() const {
    std::call_once(tables_built_, [this] { build_cell_tables(); });
    return corners_.get();
  }

 private:
  void build_cell_tables() const;

  Tool tool_;
  glm::ivec3 padded_dims_;
  std::vector<uint8_t> padded_;
  // Not zeroed on allocation: every entry is written once, in parallel
  // (a big tool's tables are a hundred megabytes), on first use.
  mutable std::once_flag tables_built_;
  mutable std::unique_ptr<uint16_t[]> cells_;
  mutable std::unique_ptr<uint64_t[]> corners_;
  // [0] nearest, [1] trilinear.
  float reach_vox_[2] = {0.0f, 0.0f};
  float core_radius_vox_[2] = {0.0f, 0.0f};
  uint8_t core_value_ = 0;
};

// The rotation kernels' batch layouts, private to the library.
namespace rotation {
struct Lines;
struct Span;
struct SpanRun;
struct Spans;
}  // namespace rotation

/// The inverse map of one placement in fixed point, over the rotated box.
class RotationFrame {
 public:
  /// Frame of `tool` rotated by `rotation` with its pivot at `position`.
  RotationFrame(const PreparedTool& tool, const glm::mat3& rotation, glm::vec3 position,
                Sampling sampling, RotationClipping clipping = RotationClipping::kReachAndCore);

  /// Target voxels that can be non-zero: the bounding box of the 8 rotated
  /// corners of the tool's support (§3.1.1).
  const Box& box() const { return box_; }
  Sampling sampling() const { return sampling_; }

  /// Writes target voxels [x0, x1) of row (y, z) (target coordinates, inside
  /// box()) into out[0 .. x1 - x0), which must hold zeros: only the stretch
  /// whose samples can be non-zero is written, the tool's core filled, the
  /// rest sampled stepping incrementally along x. Each call finds the row's
  /// reach and clips its lines anew, as sample_box() does: the reference the
  /// planned sample_row() below is tested against (the cache uses that one).
  void sample_row(const PreparedTool& tool, int y, int z, int x0, int x1, uint8_t* out) const;
  /// The whole box into out (box().size(), x fastest, zeros on entry) by
  /// Algorithm 1: the basis is inverse-rotated once; each voxel is one step
  /// along I from the previous, each row one J step, each plane one K step.
  void sample_box(const PreparedTool& tool, uint8_t* out) const;
  /// One target voxel by brute force: a full matrix product, a bounds test
  /// and a plain nearest or trilinear sample (no run skipping).
  uint8_t sample_voxel(const PreparedTool& tool, glm::ivec3 k) const;

  /// Narrows [x0, x1) (box-relative) to box-relative row (y, z)'s stretch
  /// within the tool's reach (outside it every sample is 0); false when empty.
  bool reach_span(int y, int z, int& x0, int& x1) const;

  /// What sample_row() works out for a row before sampling it, found once:
  /// the box-relative stretch [x0, x1) whose samples can be non-zero (within
  /// the reach ball and the tool's support; x0 = x1 = 0 when none) and in it
  /// the core stretch [c0, c1), filled rather than sampled (c0 = c1 = x1 when
  /// none).
  struct RowPlan {
    int16_t x0 = 0, x1 = 0, c0 = 0, c1 = 0;
  };
  /// The plans of every row of box-relative plane z: plans[y]. A cache that
  /// samples a placement's rows piecemeal (RotatedToolEntry) finds them once
  /// per placement, eight rows an instruction, rather than a square root and
  /// a clip per call.
  void row_plans(int z, RowPlan* plans) const;
  /// sample_row() of a row whose plan is `plan` (from row_plans()): the same
  /// values, without finding it again.
  void sample_row(const PreparedTool& tool, int y, int z, int x0, int x1, RowPlan plan,
                  uint8_t* out) const;

 private:
  // The stages of sample_row() and sample_box(); their batch types and
  // kernels are in core/src/tool/rotation_kernels.h.

  // The spans of the runs' rows.
  void spans(const rotation::SpanRun* runs, int count, rotation::Spans& out) const;
  // rotation::plan_row() with this frame's steps and core value, its lines
  // clipped to the tool's support when they may leave it.
  void plan_row(const int32_t row_s[3], int x0, int x1, rotation::Span span, uint8_t* out,
                rotation::Lines& lines) const;
  // plan_row() for rows i .. i + m - 1 (m <= 8) of `sp`, whole, the first at
  // row_s and writing from out (a row apart).
  void plan_rows(const int32_t row_s[3], const rotation::Spans& sp, int i, int m, uint8_t* out,
                 rotation::Lines& lines) const;
  // Narrows lines[from ..] to their samples within the tool's support and
  // drops those with none.
  void clip_lines(rotation::Lines& lines, int from) const;
  // The samples [n0, n1) of the line s + n step_[0], 0 <= n < count, within
  // the tool's support (widened by half a voxel); false when none.
  bool clip_to_support(const int32_t s[3], int count, int& n0, int& n1) const;
  // The first sample (x = 0) of box-relative row (y, z).
  void row_start(int y, int z, int32_t s[3]) const;

  Box box_;
  Sampling sampling_;
  // s(k) = origin_ + M (k - box_.lo), columns of M are the inverse-rotated
  // target basis (the paper's I, J, K), all 16.16 in padded tool voxels.
  int32_t origin_[3];
  int32_t step_[3][3];     // step_[a] = M e_a
  int32_t support_hi_[3];  // samples can be non-zero when 1 <= s >> 16 < support_hi_
  double inv_step_x_[3];
  // The ball outside which every sample is 0: the pivot's position
  // relative to box_.lo (voxel units) and PreparedTool::reach_vox(sampling)
  // squared, grown by the float rounding of spans().
  float centre_[3];
  float reach2_;
  // The core ball (same centre) shrunk by the fixed-point error bound and
  // the float rounding, squared; negative when there is none.
  float core2_;
  uint8_t core_value_;
  // Whether lines must be clipped to the tool's support: not when the reach
  // ball lies inside the padded grid, whose zero border then reads 0 anyway.
  bool clip_support_;
  // Per axis, whether the reach ball leaves the grid along it (so a line
  // can leave the support that way).
  bool clip_axis_[3];
};

/// A rotated tool: density[0] sits at target voxel `origin`.
struct RotatedTool {
  DenseGrid<uint8_t> density;
  glm::ivec3 origin{0};
};

/// Rotates the whole tool (the worst case of Table 2) by the inverse method.
/// `clipping` applies to the incremental method only (brute force never clips).
RotatedTool rotate_tool(const PreparedTool& tool, const glm::mat3& rotation, glm::vec3 position,
                        RotationMethod method, Sampling sampling,
                        RotationClipping clipping = RotationClipping::kReachAndCore);

/// Rotation about the tool's own pivot (position = pivot): quarter turns of
/// a tool whose pivot is its centre map voxels exactly onto voxels.
RotatedTool rotate_tool_about_pivot(const PreparedTool& tool, const glm::mat3& rotation,
                                    RotationMethod method, Sampling sampling,
                                    RotationClipping clipping = RotationClipping::kReachAndCore);

/// The direct (forward) method of §3.1.2, kept only as a reference that shows
/// its holes: each tool voxel is sent to the target voxel nearest to its
/// rotated centre; target voxels no tool voxel lands on stay 0. Same box and
/// origin as rotate_tool with nearest sampling.
RotatedTool rotate_tool_direct(const PreparedTool& tool, const glm::mat3& rotation,
                               glm::vec3 position);

}  // namespace sculpt::core
