// Swept strokes (stroke.h). Why a per-stroke record rather than dabs applied
// one after another: add and subtract are sums, so where consecutive dabs
// overlap the tool's antialiased rim is applied again and again; its partial
// densities saturate (a groove's wall went from 255 246 174 86 22 to
// 255 255 162 0), and the union of balls leaves a scallop between each pair
// (0.24 voxel at radius 8 and half-radius spacing). Taking, per voxel, the
// largest filling the stroke gives it and combining that once with the
// material as it was before the stroke makes the result the swept volume's,
// whatever the sample spacing, and keeps a single dab's rim.

#include "sculpt/core/sculpt/stroke.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <utility>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "saturated_run.h"
#include "sculpt/core/grid/grid_index.h"
#include "sculpt/core/sculpt/capsule_row.h"
#include "sculpt/core/sculpt/combine_row.h"
#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// The material value a voxel cannot leave under `mode`.
uint8_t saturated_value(SculptMode mode) {
  return mode == SculptMode::kAdd || mode == SculptMode::kUnion ? 255 : 0;
}

// Buffers of finished strokes, kept for the next ones on this thread: a
// stroke reaches hundreds of bricks, and three fresh 32 KiB buffers each
// (zeroed, then first touched page by page) cost more than the sweep did.
// Three a brick (the brick, its coverage, its voxels before): 50 MB.
constexpr size_t kPooledBuffers = 3 * kStrokeBufferBricksKept;
thread_local std::vector<std::vector<uint8_t>> buffer_pool;

// A buffer of `size` bytes, contents unspecified (but initialised).
std::vector<uint8_t> take_buffer(size_t size) {
  while (!buffer_pool.empty()) {
    std::vector<uint8_t> b = std::move(buffer_pool.back());
    buffer_pool.pop_back();
    if (b.size() == size) return b;
  }
  return std::vector<uint8_t>(size);
}

void give_back(std::vector<uint8_t>& buffer) {
  if (!buffer.empty() && buffer_pool.size() < kPooledBuffers)
    buffer_pool.push_back(std::move(buffer));
  buffer = {};
}

// StrokeBrick::open's mark of a row not yet looked at (bricks are narrower,
// asserted).
constexpr uint8_t kOpenUnset = 255;

// What one apply() of many samples (SweptStroke::add()) combines at most:
// segments, and rows of their sweeps' span tables (16 bytes each: 16 MiB).
// A 32-voxel ball's segment has about a thousand rows, the biggest tool's
// about twenty thousand.
constexpr size_t kBatchSegments = 256;
constexpr size_t kBatchSpanRows = size_t{1} << 20;

// Bricks a segment changes at or beyond which they are combined on every core
// (as Sculptor's big dabs).
constexpr size_t kParallelBricks = 16;
// Placements of a tool (not a ball) in one apply() from which its bricks
// are combined on every core whatever their number.
constexpr size_t kParallelPlacements = 8;
// From this radius on, run_balls() is given a hard ball's stretches inside
// radius - 1 and fills their whole 8-voxel groups without measuring: a big
// press's brick rows are mostly inside (the demo's 66-voxel ball: its sweep
// 2.80 -> 2.37 ms on one thread). Smaller balls' rows are measured whole, a
// vector at a time: finding their inside stretches cost more than it saved
// (the 12.8-voxel ball's 100-sample stroke 8-10% slower at radius 8).
constexpr float kLeanInsideRadius = 24.0f;

// Distance from p to the segment a + t ab, t in [0, 1]; ab2 = |ab|^2.
inline float segment_distance(glm::vec3 p, glm::vec3 a, glm::vec3 ab, float ab2) {
  const glm::vec3 ap = p - a;
  const float t = ab2 > 0.0f ? std::clamp(glm::dot(ap, ab) / ab2, 0.0f, 1.0f) : 0.0f;
  const glm::vec3 d = ap - t * ab;
  return std::sqrt(glm::dot(d, d));
}

Box box_around(glm::vec3 lo, glm::vec3 hi, float margin) {
  return Box{glm::ivec3(glm::floor(lo - margin)), glm::ivec3(glm::ceil(hi + margin)) + 1};
}

}  // namespace

// One swept volume of a segment: the ball's capsule, or the tool's placements
// along it.
struct SweptStroke::Sweep {
  int64_t index = 0;  // the stroke's segment it sweeps
  bool ball = false;
  // Ball: the capsule a -> b of radius `radius`, reaching `reach`.
  glm::vec3 a{0.0f}, b{0.0f};
  float radius = 0.0f, reach = 0.0f, hardness = 1.0f;
  // Ball: per row (y, z) of `box`, y fastest, the stretch [x, y) of voxels
  // to measure and within it [z, w) to fill with 255 (empty when x >= y):
  // solved once per segment, shared by its bricks.
  std::vector<glm::ivec4> spans;
  // Tool: its placements (entries kept alive while the segment is applied).
  std::vector<RotatedToolCache::Placement> placements;
  RotatedToolCache* cache = nullptr;  // theirs: counts the rows they rotate
  Box box;                            // material voxels it can reach, in the volume

  // Ball: row (y, z)'s entry of `spans`, empty outside the box.
  glm::ivec4 span(int y, int z) const {
    if (y < box.lo.y || y >= box.hi.y || z < box.lo.z || z >= box.hi.z) return glm::ivec4(0);
    return spans[static_cast<size_t>(z - box.lo.z) * (box.hi.y - box.lo.y) + (y - box.lo.y)];
  }
};

// What the stroke holds of one brick it reached.
struct SweptStroke::StrokeBrick {
  uint64_t version = 0;           // the volume's brick version when last stored
  std::vector<uint8_t> before;    // the material before the stroke (not accumulating)
  std::vector<uint8_t> current;   // the brick as stored now
  std::vector<uint8_t> coverage;  // largest filling so far, or the last segment's
  // Not accumulating, balls: per row, [open[2 r], open[2 r + 1]) holds the
  // voxels of `before` not saturated (kOpenUnset: not yet found).
  std::vector<uint8_t> open;
  int64_t segment = -1;  // accumulating: the segment `coverage` is of
};

SweptStroke::SweptStroke(Sculptor& sculptor, const StrokeOptions& options)
    : sculptor_(sculptor), options_(options) {
  assert(sculptor_.tool_ && "SweptStroke: set the sculptor's tool first");
  assert(options_.mode != SculptMode::kSmooth && "SweptStroke: smoothing is no sweep");
  own_undo_stroke_ = !sculptor_.history_.in_stroke();
  if (own_undo_stroke_) sculptor_.history_.begin_stroke();
}

SweptStroke::~SweptStroke() {
  finish();
}

void SweptStroke::finish() {
  if (!open_) return;
  open_ = false;
  if (own_undo_stroke_) sculptor_.history_.end_stroke();
  for (auto& [index, held] : bricks_) {
    give_back(held->before);
    give_back(held->current);
    give_back(held->coverage);
  }
  bricks_.clear();
  give_back(scratch_.sweep);
}

DabStats SweptStroke::add(const StrokeSample& sample) {
  return add(std::span<const StrokeSample>(&sample, 1));
}

DabStats SweptStroke::add(std::span<const StrokeSample> samples) {
  assert(open_);
  DabStats stats;
  std::vector<Segment> batch;
  auto flush = [&] {
    if (batch.empty()) return;
    stats += apply(batch);
    batch.clear();
  };
  // The rows of a segment's box, y by z, for the tool and its mirror image.
  const Tool& tool = *sculptor_.tool_;
  const float reach = tool.sphere_radius_vox > 0.0f ? tool.sphere_radius_vox + 1.0f
                                                    : sculptor_.cache_->tool().reach_vox();
  const size_t sweeps_per_segment = sculptor_.mirror_ ? 2 : 1;
  size_t batch_rows = 0;
  for (const StrokeSample& sample : samples) {
    const StrokeSample from = last_.value_or(sample);
    batch.push_back({from, sample, segment_});
    last_ = sample;
    ++segment_;
    const glm::vec3 extent =
        glm::abs(sample.position_vox - from.position_vox) + 2.0f * reach + 3.0f;
    batch_rows +=
        sweeps_per_segment * static_cast<size_t>(extent.y) * static_cast<size_t>(extent.z);
    // Accumulating, a segment builds on the material the previous one left;
    // else a batch's span tables stay bounded.
    if (options_.accumulate || batch.size() == kBatchSegments || batch_rows >= kBatchSpanRows) {
      flush();
      batch_rows = 0;
    }
  }
  flush();
  return stats;
}

DabStats SweptStroke::apply(std::span<const Segment> segments) {
  assert(!segments.empty() && (segments.size() == 1 || !options_.accumulate));
  DabStats stats;
  Volume& volume = sculptor_.volume_;
  const Tool& tool = *sculptor_.tool_;
  const SculptMode mode = options_.mode;
  const uint8_t saturated = saturated_value(mode);
  const bool accumulate = options_.accumulate;

  // The sweeps of these segments: the tool's, and its mirror image's.
  std::vector<Sweep> sweeps;
  auto add_sweep = [&](RotatedToolCache& cache, StrokeSample s0, StrokeSample s1, int64_t index) {
    Sweep sw;
    sw.index = index;
    if (tool.sphere_radius_vox > 0.0f) {
      sw.ball = true;
      sw.a = s0.position_vox;
      sw.b = s1.position_vox;
      sw.radius = tool.sphere_radius_vox;
      sw.hardness = tool.hardness;
      // tool_density() is 0 from one voxel outside the surface on.
      sw.reach = sw.radius + 1.0f;
      sw.box = box_around(glm::min(sw.a, sw.b), glm::max(sw.a, sw.b), sw.reach);
    } else {
      sw.cache = &cache;
      // Steps that move no point of the tool more than kSweepStepVox: the
      // pivot's path plus the farthest point's arc.
      const float reach = cache.tool().reach_vox();
      const float cos_half = std::min(1.0f, std::abs(glm::dot(s0.orientation, s1.orientation)));
      const float angle = 2.0f * std::acos(cos_half);
      const float travel = glm::length(s1.position_vox - s0.position_vox) + reach * angle;
      const int steps = std::max(1, static_cast<int>(std::ceil(travel / kSweepStepVox)));
      // The first sample of a stroke is one placement; a segment's start is
      // the previous segment's end, already applied.
      const bool point = travel == 0.0f;
      for (int k = point ? 0 : 1; k <= (point ? 0 : steps); ++k) {
        const float u = static_cast<float>(k) / static_cast<float>(steps);
        const glm::quat q = glm::normalize(glm::slerp(s0.orientation, s1.orientation, u));
        const glm::vec3 p = glm::mix(s0.position_vox, s1.position_vox, u);
        RotatedToolCache::Placement pl = cache.acquire(q, p);
        const Box& eb = pl.entry->box();
        sw.box = hull(sw.box, Box{eb.lo + pl.anchor, eb.hi + pl.anchor});
        sw.placements.push_back(std::move(pl));
      }
    }
    sweeps.push_back(std::move(sw));
  };
  for (const Segment& seg : segments) {
    add_sweep(*sculptor_.cache_, seg.from, seg.to, seg.index);
    if (const auto& mirror = sculptor_.mirror_) {
      const int a = mirror->axis;
      auto reflect = [&](StrokeSample s) {
        s.position_vox[a] = 2.0f * mirror->centre_vox - s.position_vox[a];
        // As Sculptor::dab(): the vector part off the mirror axis changes sign.
        for (int i = 0; i < 3; ++i)
          if (i != a) s.orientation[i] = -s.orientation[i];
        return s;
      };
      add_sweep(sculptor_.mirror_cache(a), reflect(seg.from), reflect(seg.to), seg.index);
    }
  }
  const Box volume_box{glm::ivec3(0), volume.dims()};
  bool reaches_volume = false;
  for (Sweep& sw : sweeps) {
    sw.box = intersect(sw.box, volume_box);
    reaches_volume = reaches_volume || !sw.box.empty();
  }
  if (!reaches_volume) return stats;

  // The ball's stroke, not accumulating (the station's default brush), runs
  // run_balls() below; anything else run().
  bool all_balls = true;
  for (const Sweep& sw : sweeps)
    all_balls = all_balls && sw.ball;
  const bool lean = all_balls && !accumulate;

  // Each ball's row stretches over its box (see Sweep::spans).
  for (Sweep& sw : sweeps) {
    if (!sw.ball || sw.box.empty()) continue;
    const glm::vec3 ab = sw.b - sw.a;
    const float ab2 = glm::dot(ab, ab);
    const float reach2 = sw.reach * sw.reach;
    // Within radius - 1 a hard ball's density is 255 (no square root), which
    // run() fills without measuring, and run_balls() too for the 8-voxel
    // groups inside it from kLeanInsideRadius on (capsule_row.h); smaller
    // balls' stretches it measures whole, a vector at a time.
    const bool fill_inside = sw.hardness >= 1.0f && (!lean || sw.radius >= kLeanInsideRadius);
    const float inner = fill_inside ? std::max(0.0f, sw.radius - 1.0f) : -1.0f;
    const float inner2 = inner >= 0.0f ? inner * inner : -1.0f;
    // Behind the segment's start (projection t <= 0) its filling is the
    // start ball's, which the previous segment, ending there, gave already:
    // not accumulating, only t > 0 can add anything.
    const bool skip_behind = !accumulate && sw.index > 0 && ab2 > 0.0f;
    const bool along_x = std::abs(ab.x) > 1e-3f * std::sqrt(ab2);
    const Box& rows = sw.box;
    const glm::ivec3 rn = rows.size();
    sw.spans.assign(static_cast<size_t>(rn.y) * rn.z, glm::ivec4(0, 0, 0, 0));
    if (scratch_.row_lo.size() < 2 * static_cast<size_t>(rn.y)) {
      scratch_.row_lo.resize(2 * static_cast<size_t>(rn.y));
      scratch_.row_hi.resize(2 * static_cast<size_t>(rn.y));
    }
    const float z_lo = std::min(sw.a.z, sw.b.z), z_hi = std::max(sw.a.z, sw.b.z);
    const float y_lo = std::min(sw.a.y, sw.b.y), y_hi = std::max(sw.a.y, sw.b.y);
    for (int z = rows.lo.z; z < rows.hi.z; ++z) {
      // The plane's rows within reach of the segment's y extent.
      const float fz = static_cast<float>(z);
      const float gap = fz < z_lo ? z_lo - fz : fz > z_hi ? fz - z_hi : 0.0f;
      if (gap >= sw.reach) continue;
      const float hy = std::sqrt(reach2 - gap * gap);
      const int ya = std::max(rows.lo.y, static_cast<int>(std::floor(y_lo - hy)));
      const int yb = std::min(rows.hi.y, static_cast<int>(std::ceil(y_hi + hy)) + 1);
      if (ya >= yb) continue;
      const int ny = yb - ya;
      float* reach_lo = scratch_.row_lo.data();
      float* reach_hi = scratch_.row_hi.data();
      float* inner_lo = scratch_.row_lo.data() + ny;
      float* inner_hi = scratch_.row_hi.data() + ny;
      capsule_rows(sw.a, ab, ab2, ya, ny, fz, reach2, true, reach_lo, reach_hi);
      if (inner2 > 0.0f) capsule_rows(sw.a, ab, ab2, ya, ny, fz, inner2, false, inner_lo, inner_hi);
      for (int y = ya; y < yb; ++y) {
        const float fy = static_cast<float>(y);
        const float kyz = (fy - sw.a.y) * ab.y + (fz - sw.a.z) * ab.z;
        if (skip_behind && !along_x && kyz <= 0.0f) continue;
        // The row's stretch within reach, widened by a voxel against float
        // rounding (its voxels are measured one by one).
        const float rlo = reach_lo[y - ya], rhi = reach_hi[y - ya];
        if (rlo > rhi) continue;
        int lo = floor_int(rlo) - 1;
        int hi = ceil_int(rhi) + 2;
        if (skip_behind && along_x) {
          // t(x) = ((x - a.x) ab.x + kyz) / ab2 is 0 at x_start.
          const float x_start = sw.a.x - kyz / ab.x;
          if (ab.x > 0.0f)
            lo = std::max(lo, floor_int(x_start) - 1);
          else
            hi = std::min(hi, ceil_int(x_start) + 2);
        }
        if (lo >= hi) continue;
        // A hard ball's stretch within radius - 1, narrowed by a voxel, is
        // filled without measuring.
        int in_lo = hi, in_hi = hi;
        if (inner2 > 0.0f && inner_lo[y - ya] <= inner_hi[y - ya]) {
          in_lo = ceil_int(inner_lo[y - ya]) + 1;
          in_hi = floor_int(inner_hi[y - ya]);
        }
        sw.spans[static_cast<size_t>(z - rows.lo.z) * rn.y + (y - rows.lo.y)] =
            glm::ivec4(lo, hi, in_lo, in_hi);
      }
    }
  }

  // Accumulating there is one segment; the coverage records which.
  const int64_t first_index = segments.front().index;
  const int edge = volume.brick_edge();
  assert(edge < kOpenUnset);
  const size_t brick_bytes = static_cast<size_t>(edge) * edge * edge;
  const uint32_t q =
      static_cast<uint32_t>(std::lround(std::clamp(options_.strength, 0.0f, 1.0f) * 256.0f));

  // The bricks the segments can change, with what the stroke holds of them
  // and the sweeps that reach them.
  struct Job {
    glm::ivec3 b;
    Box bb;  // the part of the brick its sweeps can reach
    StrokeBrick* held;
    std::vector<uint32_t> sweeps;
    // Per entry of `sweeps`, the rotated rows this brick asked its tool's
    // cache for: the caches take the sums after the bricks are done (the
    // bricks run on several threads, the cache's counts are not atomic).
    std::vector<RotatedToolCacheStats> row_counts;
    int64_t changed = 0;
    Box touched{glm::ivec3(std::numeric_limits<int>::max()),
                glm::ivec3(std::numeric_limits<int>::min())};
    // Its voxels as stored, for the mesher (SculptorOptions::hand_over_voxels).
    std::vector<uint8_t> handed = {};
  };
  std::vector<Job> jobs;
  std::unordered_map<int64_t, size_t> job_of;  // brick index -> jobs
  // First reached, or stored since: decoded after the loop.
  std::vector<std::pair<glm::ivec3, StrokeBrick*>> to_decode;
  const int64_t t_decode = now_ns();
  for (uint32_t si = 0; si < sweeps.size(); ++si) {
    const Sweep& sw = sweeps[si];
    if (sw.box.empty()) continue;
    const Box bricks = volume.bricks_overlapping(sw.box);
    for (int bz = bricks.lo.z; bz < bricks.hi.z; ++bz)
      for (int by = bricks.lo.y; by < bricks.hi.y; ++by)
        for (int bx = bricks.lo.x; bx < bricks.hi.x; ++bx) {
          const glm::ivec3 b(bx, by, bz);
          const Box bb = intersect(volume.brick_box(b), sw.box);
          // Beyond the sweep's reach nothing changes.
          if (sw.ball) {
            const glm::vec3 centre = (glm::vec3(bb.lo) + glm::vec3(bb.hi - 1)) * 0.5f;
            const float half_diagonal = 0.5f * glm::length(glm::vec3(bb.size()));
            const glm::vec3 ab = sw.b - sw.a;
            if (segment_distance(centre, sw.a, ab, glm::dot(ab, ab)) > sw.reach + half_diagonal)
              continue;
          }
          const auto index = static_cast<int64_t>(grid_index(b, volume.brick_grid()));
          if (auto j = job_of.find(index); j != job_of.end()) {
            Job& job = jobs[j->second];
            job.bb = hull(job.bb, bb);
            job.sweeps.push_back(si);
            continue;
          }
          ++stats.bricks_overlapped;
          auto it = bricks_.find(index);
          if (it == bricks_.end()) {
            const Brick& brick = volume.brick(b);
            if (brick.is_uniform() && brick.uniform_value() == saturated) continue;
            it = bricks_.emplace(index, std::make_unique<StrokeBrick>()).first;
          }
          StrokeBrick& held = *it->second;
          // First reached, or stored since by something else (asserted not
          // to happen in a stroke, but a stale copy must never be written
          // back).
          if (held.current.empty() || held.version != volume.brick_version(b)) {
            if (held.current.empty()) {
              held.current = take_buffer(brick_bytes + kCombineRowSlack);
              held.coverage = take_buffer(brick_bytes + kCombineRowSlack);
              if (!accumulate) held.before = take_buffer(brick_bytes + kCombineRowSlack);
            }
            to_decode.emplace_back(b, &held);
            held.version = volume.brick_version(b);
            held.open.clear();
            held.segment = -1;
            ++stats.bricks_decoded;
          } else {
            ++stats.bricks_reused;
          }
          job_of.emplace(index, jobs.size());
          jobs.push_back({b, bb, &held, {si}, {}});
        }
  }
  // A big ball's first segment reaches a hundred bricks; each decode reads
  // only the volume and writes only its brick's buffers, so they share the
  // cores.
  const auto decode = [&](int64_t k) {
    const auto& [b, held_ptr] = to_decode[static_cast<size_t>(k)];
    StrokeBrick& held = *held_ptr;
    volume.decode_brick(b, std::span<uint8_t>(held.current).first(brick_bytes));
    if (!accumulate) std::copy(held.current.begin(), held.current.end(), held.before.begin());
    // run_balls() clears a row's coverage when it first reaches it.
    if (!lean) std::fill(held.coverage.begin(), held.coverage.end(), uint8_t{0});
  };
  if (to_decode.size() >= kParallelBricks) {
    parallel_for(static_cast<int64_t>(to_decode.size()), decode);
  } else {
    for (size_t k = 0; k < to_decode.size(); ++k)
      decode(static_cast<int64_t>(k));
  }
  stats.decode_ns += now_ns() - t_decode;

  // One brick's part of the segment: its sweeps' filling, combined.
  // On a thread's Scratch, kept across the bricks (and, on this thread,
  // the segments): four fresh row tables per brick cost about as much as
  // measuring a short segment.
  auto run = [&](Job& job, Scratch& scratch) {
    std::vector<uint8_t>& sweep = scratch.sweep;
    std::vector<uint8_t>& row_buf = scratch.row_buf;
    StrokeBrick& held = *job.held;
    const glm::ivec3 origin = job.b * edge;
    const Box& bb = job.bb;
    const uint8_t* reference = accumulate ? held.current.data() : held.before.data();
    auto at = [&](int x, int y, int z) {
      return (static_cast<size_t>(z - origin.z) * edge + static_cast<size_t>(y - origin.y)) * edge +
             static_cast<size_t>(x - origin.x);
    };
    // Per row of bb, the stretch [x0, x1) that can change (not saturated in
    // the material the result is made from), found when a sweep first
    // reaches the row (kUnset before): most rows of the box it misses.
    const glm::ivec3 n = bb.size();
    constexpr int kUnset = std::numeric_limits<int>::min();
    std::vector<int>& x0 = scratch.x0;
    std::vector<int>& x1 = scratch.x1;
    x0.assign(static_cast<size_t>(n.y) * n.z, kUnset);
    x1.resize(x0.size());
    auto trim = [&](size_t k, int y, int z) {
      if (x0[k] != kUnset) return;
      const uint8_t* r = reference + at(origin.x, y, z);
      int c0 = bb.lo.x - origin.x, c1 = bb.hi.x - origin.x;
      trim_saturated(r, saturated, c0, c1);
      x0[k] = c0 + origin.x;
      x1[k] = c1 + origin.x;
    };
    auto row_index = [&](int y, int z) {
      return static_cast<size_t>(z - bb.lo.z) * n.y + (y - bb.lo.y);
    };
    // Per row, the stretch [h0, h1) the sweeps reached: only there is the
    // sweep buffer valid (zeroed when first reached), and only there can
    // the material change. Rows the sweeps miss cost nothing further.
    std::vector<int>& h0 = scratch.h0;
    std::vector<int>& h1 = scratch.h1;
    h0.assign(x0.size(), 0);
    h1.assign(x0.size(), 0);
    auto reach_row = [&](size_t k, int y, int z, int lo, int hi) {
      uint8_t* row = &sweep[at(origin.x, y, z)];
      auto zero = [&](int a, int b) {
        if (a < b) std::memset(row + (a - origin.x), 0, static_cast<size_t>(b - a));
      };
      if (h0[k] >= h1[k]) {
        zero(lo, hi);
        h0[k] = lo;
        h1[k] = hi;
        return;
      }
      if (lo < h0[k]) {
        zero(lo, h0[k]);
        h0[k] = lo;
      }
      if (hi > h1[k]) {
        zero(h1[k], hi);
        h1[k] = hi;
      }
    };

    job.row_counts.assign(job.sweeps.size(), RotatedToolCacheStats{});
    for (size_t w = 0; w < job.sweeps.size(); ++w) {
      const uint32_t si = job.sweeps[w];
      const Sweep& sw = sweeps[si];
      if (sw.ball) {
        // Balls come here only accumulating (run_balls() takes the rest).
        assert(accumulate);
        const glm::vec3 ab = sw.b - sw.a;
        const float ab2 = glm::dot(ab, ab);
        const float reach2 = sw.reach * sw.reach;
        const float inv_ab2 = ab2 > 0.0f ? 1.0f / ab2 : 0.0f;
        // Within radius - 1 a hard ball's density is 255 (no square root).
        const bool hard = sw.hardness >= 1.0f;
        const float inner = hard ? std::max(0.0f, sw.radius - 1.0f) : -1.0f;
        const float inner2 = inner >= 0.0f ? inner * inner : -1.0f;
        for (int z = bb.lo.z; z < bb.hi.z; ++z)
          for (int y = bb.lo.y; y < bb.hi.y; ++y) {
            const glm::ivec4 sp = sw.span(y, z);
            if (sp.x >= sp.y || sp.y <= bb.lo.x || sp.x >= bb.hi.x) continue;
            const size_t k = row_index(y, z);
            trim(k, y, z);
            int lo = std::max(x0[k], sp.x);
            int hi = std::min(x1[k], sp.y);
            if (lo >= hi) continue;
            reach_row(k, y, z, lo, hi);
            const size_t row = at(origin.x, y, z);
            const int in_lo = std::clamp(sp.z, lo, hi);
            const int in_hi = std::clamp(sp.w, in_lo, hi);
            uint8_t* out = &sweep[row];
            const float apy = static_cast<float>(y) - sw.a.y;
            const float apz = static_cast<float>(z) - sw.a.z;
            const float dot_yz = apy * ab.y + apz * ab.z;
            if (in_lo < in_hi)
              std::memset(out + (in_lo - origin.x), 255, static_cast<size_t>(in_hi - in_lo));
            if (hard) {
              const CapsuleRow hr{sw.a.x, ab, inv_ab2, apy, apz, dot_yz, sw.radius, inner2, reach2};
              auto measure = [&](int xa, int xb) {
                if (xa < xb) raise_hard_capsule_row(hr, xa, xb - xa, out + (xa - origin.x));
              };
              measure(lo, in_lo < in_hi ? in_lo : hi);
              if (in_lo < in_hi) measure(in_hi, hi);
              continue;
            }
            const CapsuleRow cr{sw.a.x, ab, inv_ab2, apy, apz, dot_yz, sw.radius, -1.0f, reach2};
            for (int x = lo; x < hi; ++x) {
              if (x == in_lo) x = in_hi;
              if (x >= hi) break;
              const int i = x - origin.x;
              out[i] = std::max(out[i],
                                capsule_filling(cr, static_cast<float>(x) - sw.a.x, sw.hardness));
            }
          }
      } else {
        RotatedToolCacheStats& counts = job.row_counts[w];
        for (const RotatedToolCache::Placement& pl : sw.placements) {
          RotatedToolEntry& entry = *pl.entry;
          const Box eb{entry.box().lo + pl.anchor, entry.box().hi + pl.anchor};
          const Box part = intersect(eb, bb);
          if (part.empty()) continue;
          for (int z = part.lo.z; z < part.hi.z; ++z)
            for (int y = part.lo.y; y < part.hi.y; ++y) {
              const size_t k = row_index(y, z);
              const auto [ra, rb] = entry.reach(y - pl.anchor.y, z - pl.anchor.z);
              if (ra >= rb) continue;
              trim(k, y, z);
              int lo = std::max(x0[k], ra + pl.anchor.x);
              int hi = std::min(x1[k], rb + pl.anchor.x);
              // Not accumulating, the ends already filled fully (by this
              // segment's earlier placements or the stroke's earlier
              // segments) need no rotated voxels: a tool moving along a
              // row rotates only its leading edge.
              if (lo >= hi) continue;
              reach_row(k, y, z, lo, hi);
              if (!accumulate) {
                const uint8_t* cov = &held.coverage[at(origin.x, y, z)];
                const uint8_t* done = &sweep[at(origin.x, y, z)];
                auto full = [&](int x) {
                  return cov[x - origin.x] == 255 || done[x - origin.x] == 255;
                };
                while (lo < hi && full(lo))
                  ++lo;
                while (hi > lo && full(hi - 1))
                  --hi;
              }
              if (lo >= hi) continue;
              const uint8_t* f = entry.row(y - pl.anchor.y, z - pl.anchor.z, lo - pl.anchor.x,
                                           hi - pl.anchor.x, counts);
              uint8_t* out = &sweep[at(lo, y, z)];
              for (int i = 0; i < hi - lo; ++i)
                out[i] = std::max(out[i], f[i]);
            }
        }
      }
    }

    // Combine: once per stroke from the material before it, or building on
    // the current material by what exceeds the previous segment's filling.
    const bool prev_valid = accumulate && held.segment == first_index - 1;
    for (int z = bb.lo.z; z < bb.hi.z; ++z)
      for (int y = bb.lo.y; y < bb.hi.y; ++y) {
        const size_t k = row_index(y, z);
        const int c0 = h0[k], c1 = h1[k];
        if (c0 >= c1) continue;
        const size_t i0 = at(c0, y, z);
        const int len = c1 - c0;
        uint8_t* cur = &held.current[i0];
        uint8_t* cov = &held.coverage[i0];
        const uint8_t* sw = &sweep[i0];
        int64_t changed = 0;
        if (!accumulate) {
          // Only where this segment fills more than the stroke had.
          int f = 0, l = len;
          // Where the stroke had filled fully already, eight at a time.
          constexpr uint64_t kFull = ~uint64_t{0};
          while (f + 8 <= l && load_u64(cov + f) == kFull)
            f += 8;
          while (f < l && sw[f] <= cov[f])
            ++f;
          while (l - 8 >= f && load_u64(cov + l - 8) == kFull)
            l -= 8;
          while (l > f && sw[l - 1] <= cov[l - 1])
            --l;
          if (f == l) continue;
          for (int i = f; i < l; ++i)
            cov[i] = std::max(cov[i], sw[i]);
          std::memcpy(row_buf.data(), &held.before[i0 + static_cast<size_t>(f)],
                      static_cast<size_t>(l - f));
          combine_row(mode, row_buf.data(), cov + f, l - f, q);
          for (int i = f; i < l; ++i)
            changed += row_buf[i - f] != cur[i];
          if (changed != 0) std::memcpy(cur + f, row_buf.data(), static_cast<size_t>(l - f));
          // What was re-encoded must cover what changed: this row's [f, l).
          if (changed != 0) {
            job.changed += changed;
            job.touched.lo = glm::min(job.touched.lo, glm::ivec3(c0 + f, y, z));
            job.touched.hi = glm::max(job.touched.hi, glm::ivec3(c0 + l, y + 1, z + 1));
          }
          continue;
        } else {
          for (int i = 0; i < len; ++i) {
            const uint8_t prev = prev_valid ? cov[i] : uint8_t{0};
            row_buf[i] = sw[i] > prev ? static_cast<uint8_t>(sw[i] - prev) : uint8_t{0};
          }
          changed = combine_row(mode, cur, row_buf.data(), len, q);
        }
        if (changed != 0) {
          job.changed += changed;
          job.touched.lo = glm::min(job.touched.lo, glm::ivec3(c0, y, z));
          job.touched.hi = glm::max(job.touched.hi, glm::ivec3(c1, y + 1, z + 1));
        }
      }
    if (accumulate) {
      // The coverage becomes this segment's alone.
      std::fill(held.coverage.begin(), held.coverage.end(), uint8_t{0});
      for (int z = bb.lo.z; z < bb.hi.z; ++z)
        for (int y = bb.lo.y; y < bb.hi.y; ++y) {
          const size_t k = row_index(y, z);
          if (h0[k] < h1[k])
            std::memcpy(&held.coverage[at(h0[k], y, z)], &sweep[at(h0[k], y, z)],
                        static_cast<size_t>(h1[k] - h0[k]));
        }
      held.segment = first_index;
    }
  };

  // The ball's stroke, not accumulating (the station's default brush): each
  // sweep's filling of a row goes to a row buffer and the coverage takes the
  // larger, row by row of the sweep's own rows; then each row where the
  // coverage grew is combined once from the material before the stroke. The
  // same bytes as run() gave here (every bundled session replays to the
  // volume it did), without its brick-sized sweep buffer: a segment mostly
  // adds a leading rim to rows the stroke reached before.
  auto run_balls = [&](Job& job, Scratch& scratch) {
    StrokeBrick& held = *job.held;
    const glm::ivec3 origin = job.b * edge;
    const Box& bb = job.bb;
    uint8_t* fill = scratch.row_fill.data();
    uint8_t* row_buf = scratch.row_buf.data();
    const int bx0 = bb.lo.x - origin.x, bx1 = bb.hi.x - origin.x;
    // Per row of bb, where the coverage grew [g0, g1) (brick x), and the
    // rows where it did (a segment reaches a few of a brick's rows).
    const glm::ivec3 n = bb.size();
    std::vector<int>& grew0 = scratch.h0;
    std::vector<int>& grew1 = scratch.h1;
    std::vector<int>& grown_rows = scratch.grown_rows;
    grew0.assign(static_cast<size_t>(n.y) * n.z, edge);
    grew1.assign(grew0.size(), 0);
    grown_rows.clear();
    // Per brick row, the stretch not saturated before the stroke (found
    // when a sweep first reaches the row, kept for the stroke's later
    // segments: the material before it does not change).
    if (held.open.empty()) held.open.assign(2 * static_cast<size_t>(edge) * edge, kOpenUnset);
    auto row_at = [&](int y, int z) {
      return (static_cast<size_t>(z - origin.z) * edge + static_cast<size_t>(y - origin.y)) * edge;
    };
    for (const uint32_t si : job.sweeps) {
      const Sweep& sw = sweeps[si];
      const Box part = intersect(sw.box, bb);
      const int span_ny = sw.box.size().y;
      const glm::vec3 ab = sw.b - sw.a;
      const float ab2 = glm::dot(ab, ab);
      const float inv_ab2 = ab2 > 0.0f ? 1.0f / ab2 : 0.0f;
      const float reach2 = sw.reach * sw.reach;
      const bool hard = sw.hardness >= 1.0f;
      const float inner = std::max(0.0f, sw.radius - 1.0f);
      for (int z = part.lo.z; z < part.hi.z; ++z)
        for (int y = part.lo.y; y < part.hi.y; ++y) {
          const glm::ivec4 sp =
              sw.spans[static_cast<size_t>(z - sw.box.lo.z) * span_ny + (y - sw.box.lo.y)];
          int lo = std::max(sp.x - origin.x, bx0), hi = std::min(sp.y - origin.x, bx1);
          if (lo >= hi) continue;
          const size_t k = static_cast<size_t>(z - bb.lo.z) * n.y + (y - bb.lo.y);
          const size_t row = row_at(y, z);
          uint8_t* cov = &held.coverage[row];
          uint8_t* open =
              &held.open[2 * (static_cast<size_t>(z - origin.z) * edge + (y - origin.y))];
          if (open[0] == kOpenUnset) {
            std::memset(cov, 0, static_cast<size_t>(edge));
            int c0 = 0, c1 = edge;
            trim_saturated(&held.before[row], saturated, c0, c1);
            open[0] = static_cast<uint8_t>(c0);
            open[1] = static_cast<uint8_t>(c1);
          }
          lo = std::max(lo, static_cast<int>(open[0]));
          hi = std::min(hi, static_cast<int>(open[1]));
          // (Voxels the stroke filled fully cannot grow: the kernel leaves
          // them, and trimming them off the ends first measured slower.)
          if (lo >= hi) continue;
          const float apy = static_cast<float>(y) - sw.a.y;
          const float apz = static_cast<float>(z) - sw.a.z;
          const float dot_yz = apy * ab.y + apz * ab.z;
          // Where this sweep fills more than the stroke had: the row's grown
          // stretch spans every sweep's (a mirror image's may lie before or
          // after the tool's along the row, or overlap it).
          GrownStretch grown;
          // The stretch inside radius - 1 (with a voxel to spare, see
          // Sweep::spans; empty for a soft ball or a small hard one): 255
          // without measuring.
          const int in_lo = std::clamp(sp.z - origin.x, lo, hi);
          const int in_hi = std::clamp(sp.w - origin.x, in_lo, hi);
          if (hard) {
            const CapsuleRow hr{sw.a.x, ab,        inv_ab2,       apy,   apz,
                                dot_yz, sw.radius, inner * inner, reach2};
            grown = grow_hard_capsule_row(hr, origin.x, lo, hi, cov, fill, in_lo, in_hi);
          } else {
            std::memset(fill + lo, 0, static_cast<size_t>(hi - lo));
            if (in_lo < in_hi) std::memset(fill + in_lo, 255, static_cast<size_t>(in_hi - in_lo));
            const CapsuleRow cr{sw.a.x, ab, inv_ab2, apy, apz, dot_yz, sw.radius, -1.0f, reach2};
            for (int x = lo; x < hi; ++x) {
              if (cov[x] == 255) continue;  // nothing can add to it
              fill[x] = std::max(
                  fill[x],
                  capsule_filling(cr, static_cast<float>(x + origin.x) - sw.a.x, sw.hardness));
            }
            grown = raise_coverage(fill, cov, lo, hi);
          }
          if (grown.begin >= grown.end) continue;
          if (grew0[k] >= grew1[k]) grown_rows.push_back(static_cast<int>(k));
          grew0[k] = std::min(grew0[k], grown.begin);
          grew1[k] = std::max(grew1[k], grown.end);
        }
    }
    for (const int k : grown_rows) {
      const int y = bb.lo.y + k % n.y, z = bb.lo.z + k / n.y;
      const int g0 = grew0[k], g1 = grew1[k];
      const size_t row = row_at(y, z);
      const int len = g1 - g0;
      std::memcpy(row_buf, &held.before[row + g0], static_cast<size_t>(len));
      combine_row(mode, row_buf, &held.coverage[row + g0], len, q);
      uint8_t* cur = &held.current[row];
      int64_t changed = 0;
      for (int i = 0; i < len; ++i)
        changed += row_buf[i] != cur[g0 + i];
      if (changed == 0) continue;
      std::memcpy(cur + g0, row_buf, static_cast<size_t>(len));
      job.changed += changed;
      job.touched.lo = glm::min(job.touched.lo, glm::ivec3(origin.x + g0, y, z));
      job.touched.hi = glm::max(job.touched.hi, glm::ivec3(origin.x + g1, y + 1, z + 1));
    }
  };

  const int64_t t_apply = now_ns();
  // A ball's sweep reads nothing shared; a rotated tool's rows are filled
  // lazily in entries the bricks share, which threads may fill at once
  // (RotatedToolEntry): a turning tool's segment rotates dozens of
  // placements, the work of its bricks.
  const bool hand_over = sculptor_.options_.hand_over_voxels;
  auto run_job = [&](Job& job, Scratch& scratch) {
    if (lean) {
      run_balls(job, scratch);
    } else {
      run(job, scratch);
    }
    // Copied here, on every thread, not as the bricks are stored one by one.
    if (hand_over && job.changed != 0)
      job.handed.assign(job.held->current.begin(),
                        job.held->current.begin() + static_cast<std::ptrdiff_t>(brick_bytes));
  };
  const size_t row_bytes = static_cast<size_t>(edge) + kCombineRowSlack;
  // A turning tool's segment is work enough on a few bricks: each of its
  // placements rotates the tool's rows anew.
  size_t placements = 0;
  for (const Sweep& sw : sweeps)
    placements += sw.placements.size();
  if (jobs.size() >= kParallelBricks || (jobs.size() >= 2 && placements >= kParallelPlacements)) {
    parallel_for(static_cast<int64_t>(jobs.size()), [&](int64_t k) {
      Scratch scratch;
      if (!lean) scratch.sweep = take_buffer(brick_bytes + kCombineRowSlack);
      scratch.row_buf.resize(row_bytes);
      scratch.row_fill.resize(row_bytes);
      run_job(jobs[static_cast<size_t>(k)], scratch);
      give_back(scratch.sweep);
    });
  } else {
    if (!lean && scratch_.sweep.size() != brick_bytes + kCombineRowSlack)
      scratch_.sweep = take_buffer(brick_bytes + kCombineRowSlack);
    scratch_.row_buf.resize(row_bytes);
    scratch_.row_fill.resize(row_bytes);
    for (Job& job : jobs)
      run_job(job, scratch_);
  }
  for (const Job& job : jobs)
    for (size_t k = 0; k < job.row_counts.size(); ++k)
      if (RotatedToolCache* cache = sweeps[job.sweeps[k]].cache)
        cache->add_row_counts(job.row_counts[k]);
  stats.apply_ns += now_ns() - t_apply;

  const int64_t t_store = now_ns();
  std::vector<Volume::BrickStore> stores;
  for (Job& job : jobs) {
    if (job.changed == 0) continue;
    sculptor_.history_.before_change(volume, job.b);
    stores.push_back(
        {job.b, std::span<uint8_t>(job.held->current).first(brick_bytes), job.touched});
    ++stats.bricks_changed;
    stats.voxels_changed += job.changed;
  }
  // The versions the changed voxels are held against (a brick stored by
  // something else since was decoded again: its current version). A brick
  // reaching past the volume has its outside re-padded as it is stored,
  // beyond the rows it changed: not said.
  std::vector<std::optional<uint64_t>> changed_from;
  for (const Job& job : jobs) {
    if (job.changed == 0) continue;
    const bool inside = glm::all(glm::lessThanEqual((job.b + 1) * edge, volume.dims()));
    changed_from.push_back(inside ? std::optional(volume.brick_version(job.b)) : std::nullopt);
  }
  volume.store_bricks(stores);
  size_t stored = 0;
  for (Job& job : jobs) {
    if (job.changed == 0) continue;
    job.held->version = volume.brick_version(job.b);
    if (hand_over)
      sculptor_.hand_over(job.b, StoredVoxels{job.held->version, std::move(job.handed),
                                              changed_from[stored], job.touched});
    ++stored;
  }
  stats.encode_ns += now_ns() - t_store;
  return stats;
}

void keep_stroke_buffers(int brick_edge, size_t bricks) {
  const size_t size = static_cast<size_t>(brick_edge) * brick_edge * brick_edge + kCombineRowSlack;
  const size_t count = std::min(kPooledBuffers, 3 * bricks);
  buffer_pool.reserve(kPooledBuffers);
  while (buffer_pool.size() < count)
    buffer_pool.emplace_back(size);
}

size_t stroke_buffers_kept() {
  return buffer_pool.size();
}

DabStats sweep_stroke(Sculptor& sculptor, std::span<const StrokeSample> path,
                      const StrokeOptions& options) {
  assert(!path.empty());
  DabStats stats;
  SweptStroke stroke(sculptor, options);
  stats += stroke.add(path);
  stroke.finish();
  return stats;
}

}  // namespace sculpt::core
