#pragma once
// Swept strokes: between two consecutive samples of a stroke the tool's
// continuous swept volume is applied, not a row of dabs, so a stroke leaves
// no scallop at any sample spacing (issue 21).
//
// For a make_sphere_tool() ball the sweep is exact: a capsule, each voxel's
// filling the ball's tool_density() of its distance to the segment (the same
// 2-voxel antialiased rim, or falloff, as a single dab's). Any other tool is
// placed along the segment, orientation slerped, at steps that move no point
// of the tool more than kSweepStepVox, and each voxel takes the largest
// filling of those placements.
//
// Within one stroke overlapping parts do not accumulate (the strength applies
// once per stroke, as in Blender's default): the stroke keeps, per voxel it
// reached, the material as it was before the stroke and the largest tool
// filling the stroke has given it so far, and the voxel is always
// mode(before, strength * largest filling). With `accumulate` each segment
// instead builds on the material the previous one left, adding only what its
// sweep gives beyond the previous segment's (so a segment's joint with the
// next is not applied twice), and a stroke crossing itself builds up.
//
// A stroke is one undo step (part of the Sculptor's open stroke if one is
// open), and with a mirror plane set the mirrored sweep joins the same
// coverage, so where the two overlap the operation applies once.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "sculpt/core/sculpt/sculptor.h"

namespace sculpt::core {

/// Largest move of any point of a (non-ball) tool between two placements of
/// its sweep, in voxels: a quarter of the 2-voxel rim. The scallop between
/// placements of a surface of curvature radius r is 0.5^2 / (8 r) voxel
/// (0.004 at r = 8), far below what a mesh shows; a sharp corner's trace
/// keeps its antialiased rim.
inline constexpr float kSweepStepVox = 0.5f;

/// One sample of a stroke's path: where the tool's pivot goes (material voxel
/// units) and the tool-to-material rotation (unit quaternion).
struct StrokeSample {
  glm::vec3 position_vox{0.0f};
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};
};

struct StrokeOptions {
  /// add, subtract, union or difference (kSmooth is no sweep; asserted).
  SculptMode mode = SculptMode::kAdd;
  /// Scales the tool's filling, in [0, 1].
  float strength = 1.0f;
  /// false: a voxel gets the most the stroke's tool gave it (once per stroke);
  /// true: segments build up where the stroke overlaps itself.
  bool accumulate = false;
};

/// A stroke in progress on a Sculptor (its volume, tool, sampling, mirror and
/// undo history). The sculptor and its tool must not change while it lives.
class SweptStroke {
 public:
  SweptStroke(Sculptor& sculptor, const StrokeOptions& options);
  /// Closes the stroke (finish()).
  ~SweptStroke();
  SweptStroke(const SweptStroke&) = delete;
  SweptStroke& operator=(const SweptStroke&) = delete;

  /// The next sample: the first applies the tool there, each later one the
  /// sweep from the previous sample to it.
  DabStats add(const StrokeSample& sample);
  /// The next samples at once, with the same material as adding them one by
  /// one: not accumulating, each voxel ends as the mode of its material
  /// before the stroke and the largest filling of all the stroke's sweeps,
  /// whatever their order. Each brick the samples reach is combined and
  /// stored once (an undo copy, a wavelet encode) instead of once per
  /// segment. Accumulating, the segments are applied one after another.
  DabStats add(std::span<const StrokeSample> samples);
  /// Ends the stroke: its undo step is closed (unless it joined one opened
  /// by Sculptor::begin_stroke()) and its per-voxel records are dropped.
  void finish();

  /// Voxel-bricks whose before-stroke material and coverage this stroke holds.
  size_t bricks_held() const { return bricks_.size(); }

 private:
  struct Sweep;
  struct StrokeBrick;
  // The sweep from one sample to the next, the stroke's index-th.
  struct Segment {
    StrokeSample from, to;
    int64_t index = 0;
  };
  // One thread's buffers for a brick of a segment: its filling, a row, and
  // per-row tables (the ball's lean path: the two rows, h0/h1 and grown_rows).
  struct Scratch {
    std::vector<uint8_t> sweep, row_buf, row_fill;
    std::vector<int> x0, x1, h0, h1;
    std::vector<int> grown_rows;        // the ball's lean path: rows whose coverage grew
    std::vector<float> row_lo, row_hi;  // a plane's row stretches (spans)
  };
  // The segments' sweeps (at most one when accumulating), combined together.
  DabStats apply(std::span<const Segment> segments);

  Sculptor& sculptor_;
  StrokeOptions options_;
  bool own_undo_stroke_ = false;
  bool open_ = true;
  std::optional<StrokeSample> last_;
  int64_t segment_ = 0;
  std::unordered_map<int64_t, std::unique_ptr<StrokeBrick>> bricks_;
  Scratch scratch_;  // the segment's bricks one after another on this thread
};

/// The stroke through `path` (at least one sample) in one go.
DabStats sweep_stroke(Sculptor& sculptor, std::span<const StrokeSample> path,
                      const StrokeOptions& options);

/// Fills the calling thread's pool of stroke buffers with buffers for
/// `bricks` bricks of `brick_edge` voxels (three each: the brick, its
/// coverage, its voxels before the stroke), as finished strokes leave them.
/// A thread that must answer at once calls it when it starts: a session's
/// first strokes otherwise allocate and zero every buffer as they reach
/// their bricks (the demo's first ball, 112 bricks: 1.4 ms of its 5 ms).
void keep_stroke_buffers(int brick_edge, size_t bricks);
/// The most bricks whose buffers a thread's pool holds (three each): the
/// bust's 110-voxel ball reaches several hundred. A pool filled for more
/// holds this many.
inline constexpr size_t kStrokeBufferBricksKept = 512;
/// Buffers in the calling thread's pool (at most 3 x kStrokeBufferBricksKept).
size_t stroke_buffers_kept();

}  // namespace sculpt::core
