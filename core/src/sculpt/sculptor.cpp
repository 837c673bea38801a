#include "sculpt/core/sculpt/sculptor.h"
#include "sculpt/core/grid/grid_index.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>

#include "saturated_run.h"
#include "sculpt/core/sculpt/combine_row.h"
#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// floor and ceil to int without libm calls (no rounding instruction on the
// baseline x86-64 target), for coordinates well inside the int range.
inline int floor_int(float x) {
  const int i = static_cast<int>(x);
  return i - (x < static_cast<float>(i));
}
inline int ceil_int(float x) {
  const int i = static_cast<int>(x);
  return i + (x > static_cast<float>(i));
}

// Dabs that change at least this many bricks are combined on every core.
constexpr int kParallelBricks = 16;

// Whether a uniform brick of value v can change under `mode`.
bool can_change_uniform(SculptMode mode, uint8_t v) {
  switch (mode) {
    case SculptMode::kAdd:
    case SculptMode::kUnion:
      return v != 255;
    case SculptMode::kSubtract:
    case SculptMode::kDifference:
      return v != 0;
    case SculptMode::kSmooth:
      return true;
  }
  return true;
}

// The material value a voxel must differ from to be in contact (a voxel at
// that value cannot change), or -1 when every voxel is.
int saturated_value(SculptMode mode) {
  switch (mode) {
    case SculptMode::kAdd:
    case SculptMode::kUnion:
      return 255;
    case SculptMode::kSubtract:
    case SculptMode::kDifference:
      return 0;
    case SculptMode::kSmooth:
      return -1;
  }
  return -1;
}

static_assert(RotatedToolEntry::kRowSlack >= kCombineRowSlack,
              "combine_row() reads past the rotated tool's rows");

// Filling a of tool value f at strength q/256 (q = 256 keeps f exactly).
inline uint32_t filling(uint8_t f, uint32_t q) {
  return (f * q + 128) >> 8;
}

// Moves each voxel toward the mean of its 3x3x3 neighbourhood in `before`
// (the material before the dab; p is the first voxel's index in it) by the
// filling fraction.
int64_t smooth_row(uint8_t* m, const uint8_t* f, int n, uint32_t q,
                   const DenseGrid<uint8_t>& before, glm::ivec3 p) {
  int64_t changed = 0;
  for (int i = 0; i < n; ++i, ++p.x) {
    const int a = static_cast<int>(filling(f[i], q));
    if (a == 0) continue;
    int sum = 0;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          sum += before.at(p.x + dx, p.y + dy, p.z + dz);
    // Outside the volume reads 0: a smoothed border erodes, as a blur of the
    // object in empty space would.
    const int v = m[i];
    const int delta = (sum + 13) / 27 - v;
    const int r = std::clamp(v + (a * delta + (delta >= 0 ? 127 : -127)) / 255, 0, 255);
    changed += r != v;
    m[i] = static_cast<uint8_t>(r);
  }
  return changed;
}

}  // namespace

std::optional<SculptMode> parse_sculpt_mode(const std::string& name) {
  for (SculptMode m : {SculptMode::kAdd, SculptMode::kSubtract, SculptMode::kUnion,
                       SculptMode::kDifference, SculptMode::kSmooth}) {
    if (name == sculpt_mode_name(m)) return m;
  }
  return std::nullopt;
}

const char* sculpt_mode_name(SculptMode mode) {
  switch (mode) {
    case SculptMode::kAdd:
      return "add";
    case SculptMode::kSubtract:
      return "subtract";
    case SculptMode::kUnion:
      return "union";
    case SculptMode::kDifference:
      return "difference";
    case SculptMode::kSmooth:
      return "smooth";
  }
  return "?";
}

void Sculptor::hand_over(glm::ivec3 b, StoredVoxels voxels) {
  if (stored_voxels_.size() >= kMaxHandedBricks) stored_voxels_.clear();  // nobody takes them
  const auto index = static_cast<int64_t>(grid_index(b, volume_.brick_grid()));
  // Stored again before they were taken: changed since the first's version.
  if (const auto it = stored_voxels_.find(index); it != stored_voxels_.end())
    follow(it->second, voxels);
  stored_voxels_.insert_or_assign(index, std::move(voxels));
}

DabStats& DabStats::operator+=(const DabStats& o) {
  bricks_overlapped += o.bricks_overlapped;
  bricks_decoded += o.bricks_decoded;
  bricks_reused += o.bricks_reused;
  bricks_changed += o.bricks_changed;
  voxels_changed += o.voxels_changed;
  decode_ns += o.decode_ns;
  apply_ns += o.apply_ns;
  encode_ns += o.encode_ns;
  return *this;
}

Sculptor::Sculptor(Volume& volume, const SculptorOptions& options)
    : volume_(volume), options_(options), history_(options.undo_max_bytes) {}

Sculptor::DecodedBrick& Sculptor::decoded_brick(glm::ivec3 b, DabStats& stats) {
  const auto index = static_cast<int64_t>(grid_index(b, volume_.brick_grid()));
  auto it = decoded_.find(index);
  if (it == decoded_.end()) {
    if (decoded_.size() >= options_.decoded_bricks) {
      auto oldest = decoded_.begin();
      for (auto i = decoded_.begin(); i != decoded_.end(); ++i)
        if (i->second.last_use < oldest->second.last_use) oldest = i;
      decoded_.erase(oldest);
    }
    const size_t e = static_cast<size_t>(volume_.brick_edge());
    it = decoded_.emplace(index, DecodedBrick{}).first;
    // combine_row() reads and rewrites up to kCombineRowSlack bytes past a row.
    it->second.voxels.resize(e * e * e + kCombineRowSlack);
    it->second.version = ~uint64_t{0};
  }
  DecodedBrick& d = it->second;
  d.last_use = ++use_clock_;
  // Any store since (an undo, another writer) bumps the version.
  if (d.version != volume_.brick_version(b)) {
    volume_.decode_brick(b, d.brick());
    d.version = volume_.brick_version(b);
    ++stats.bricks_decoded;
  } else {
    ++stats.bricks_reused;
  }
  return d;
}

void Sculptor::set_tool(Tool tool) {
  tool_ = std::move(tool);
  rebuild_caches();
}

void Sculptor::set_sampling(Sampling sampling) {
  options_.sampling = sampling;
  if (tool_) rebuild_caches();
}

void Sculptor::rebuild_caches() {
  retired_cache_stats_ = rotation_cache_stats().retired();
  cache_ = std::make_unique<RotatedToolCache>(std::make_shared<const PreparedTool>(*tool_),
                                              options_.sampling, options_.cache_max_bytes,
                                              options_.subvoxel_steps);
  for (auto& c : mirror_caches_)
    c.reset();
}

const RotatedToolCache& Sculptor::cache(bool mirrored) const {
  assert(cache_);
  if (mirrored && mirror_ && mirror_caches_[mirror_->axis]) return *mirror_caches_[mirror_->axis];
  return *cache_;
}

RotatedToolCacheStats Sculptor::rotation_cache_stats() const {
  RotatedToolCacheStats sum = retired_cache_stats_;
  if (cache_) sum += cache_->stats();
  for (const auto& c : mirror_caches_)
    if (c) sum += c->stats();
  return sum;
}

RotatedToolCache& Sculptor::mirror_cache(int axis) {
  auto& mc = mirror_caches_[axis];
  if (!mc) {
    mc = std::make_unique<RotatedToolCache>(
        std::make_shared<const PreparedTool>(mirror_tool(*tool_, axis)), options_.sampling,
        options_.cache_max_bytes, options_.subvoxel_steps);
  }
  return *mc;
}

DabStats Sculptor::dab(const Dab& dab) {
  assert(tool_ && "Sculptor::dab(): set_tool() first");
  const bool own_stroke = !history_.in_stroke();
  if (own_stroke) history_.begin_stroke();
  DabStats stats = apply(*cache_, dab);
  if (mirror_) {
    const int a = mirror_->axis;
    RotatedToolCache& mc = mirror_cache(a);
    Dab m = dab;
    m.position_vox[a] = 2.0f * mirror_->centre_vox - dab.position_vox[a];
    // Reflection M turns rotation R into M R M: the rotation about the
    // reflected axis by the opposite angle, i.e. the quaternion's vector
    // components off the mirror axis change sign.
    glm::quat q = dab.orientation;
    for (int i = 0; i < 3; ++i)
      if (i != a) q[i] = -q[i];  // glm::quat indexes x, y, z, w
    m.orientation = q;
    stats += apply(mc, m);
  }
  if (own_stroke) history_.end_stroke();
  return stats;
}

DabStats Sculptor::apply(RotatedToolCache& cache, const Dab& dab) {
  DabStats stats;
  const RotatedToolCache::Placement placement = cache.acquire(dab.orientation, dab.position_vox);
  RotatedToolEntry& entry = *placement.entry;
  const glm::ivec3 anchor = placement.anchor;
  // §3.3: collision of the rotated tool's box with the material's box.
  const Box region = intersect(Box{entry.box().lo + anchor, entry.box().hi + anchor},
                               Box{glm::ivec3(0), volume_.dims()});
  if (region.empty()) return stats;

  const uint32_t strength_q =
      static_cast<uint32_t>(std::lround(std::clamp(dab.strength, 0.0f, 1.0f) * 256.0f));
  const glm::vec3 pivot_pos = glm::vec3(anchor) + entry.offset();
  const float reach2 = cache.tool().reach_vox() * cache.tool().reach_vox();
  const int saturated = saturated_value(dab.mode);
  // Smoothing reads neighbours as they were before this dab, across bricks.
  DenseGrid<uint8_t> before;
  const Box before_box{region.lo - 1, region.hi + 1};
  if (dab.mode == SculptMode::kSmooth) before = volume_.read(before_box, 0);

  const int edge = volume_.brick_edge();
  // The new voxels of one brick's part `bb` of the region, in `voxels` (the
  // brick's, edge^3 plus kCombineRowSlack), counting rotated rows in
  // `rows`; returns the voxels changed and the box of the rows that did.
  struct Combined {
    int64_t changed = 0;
    Box touched{glm::ivec3(std::numeric_limits<int>::max()),
                glm::ivec3(std::numeric_limits<int>::min())};
  };
  auto combine_brick = [&](glm::ivec3 b, const Box& bb, uint8_t* voxels,
                           RotatedToolCacheStats& rows) {
    Combined out;
    const glm::ivec3 origin = b * edge;
    for (int z = bb.lo.z; z < bb.hi.z; ++z) {
      // Only the rows of this plane that cross the reach ball.
      const float pz = static_cast<float>(z) - pivot_pos.z;
      const float hz2 = reach2 - pz * pz;
      if (hz2 < 0.0f) continue;
      const float hz = std::sqrt(hz2);
      const int y_lo = std::max(bb.lo.y, ceil_int(pivot_pos.y - hz));
      const int y_hi = std::min(bb.hi.y, floor_int(pivot_pos.y + hz) + 1);
      for (int y = y_lo; y < y_hi; ++y) {
        // The row's stretch within the tool's reach (a ball round the
        // pivot), kept by the placement.
        const auto [ra, rb] = entry.reach(y - anchor.y, z - anchor.z);
        const int xa = std::max(bb.lo.x, ra + anchor.x);
        const int xb = std::min(bb.hi.x, rb + anchor.x);
        if (xa >= xb) continue;
        uint8_t* m = &voxels[(static_cast<size_t>(z - origin.z) * edge + (y - origin.y)) * edge +
                             (xa - origin.x)];
        // Contact: rotate only where the material can change.
        int c0 = 0, c1 = xb - xa;
        if (saturated >= 0) trim_saturated(m, static_cast<uint8_t>(saturated), c0, c1);
        if (c0 >= c1) continue;
        const uint8_t* f =
            entry.row(y - anchor.y, z - anchor.z, xa + c0 - anchor.x, xa + c1 - anchor.x, rows);
        const int64_t row_changed = dab.mode == SculptMode::kSmooth
                                        ? smooth_row(m + c0, f, c1 - c0, strength_q, before,
                                                     glm::ivec3(xa + c0, y, z) - before_box.lo)
                                        : combine_row(dab.mode, m + c0, f, c1 - c0, strength_q);
        if (row_changed != 0) {
          out.changed += row_changed;
          out.touched.lo = glm::min(out.touched.lo, glm::ivec3(xa + c0, y, z));
          out.touched.hi = glm::max(out.touched.hi, glm::ivec3(xa + c1, y + 1, z + 1));
        }
      }
    }
    return out;
  };

  // The bricks the dab can change, in brick order.
  struct Job {
    glm::ivec3 b;
    Box bb;
  };
  std::vector<Job> jobs;
  const Box bricks = volume_.bricks_overlapping(region);
  for (int bz = bricks.lo.z; bz < bricks.hi.z; ++bz)
    for (int by = bricks.lo.y; by < bricks.hi.y; ++by)
      for (int bx = bricks.lo.x; bx < bricks.hi.x; ++bx) {
        const glm::ivec3 b(bx, by, bz);
        ++stats.bricks_overlapped;
        const Box bb = intersect(volume_.brick_box(b), region);
        // Beyond the tool's reach nothing is non-zero.
        const glm::vec3 nearest = glm::clamp(pivot_pos, glm::vec3(bb.lo), glm::vec3(bb.hi - 1));
        const glm::vec3 gap = nearest - pivot_pos;
        if (glm::dot(gap, gap) > reach2) continue;
        const Brick& brick = volume_.brick(b);
        if (brick.is_uniform() && !can_change_uniform(dab.mode, brick.uniform_value())) continue;
        jobs.push_back({b, bb});
      }

  RotatedToolCacheStats rows;
  if (static_cast<int>(jobs.size()) < kParallelBricks) {
    // A usual dab: a few bricks, their decoded voxels kept for the next.
    for (const Job& job : jobs) {
      const int64_t t0 = now_ns();
      DecodedBrick& decoded = decoded_brick(job.b, stats);
      const int64_t t1 = now_ns();
      const Combined c = combine_brick(job.b, job.bb, decoded.voxels.data(), rows);
      const int64_t t2 = now_ns();
      stats.decode_ns += t1 - t0;
      stats.apply_ns += t2 - t1;
      if (c.changed == 0) continue;
      history_.before_change(volume_, job.b);
      volume_.store_brick(job.b, decoded.brick(), c.touched);  // re-pads the voxels as stored
      decoded.version = volume_.brick_version(job.b);
      stats.encode_ns += now_ns() - t2;
      ++stats.bricks_changed;
      stats.voxels_changed += c.changed;
    }
    cache.add_row_counts(rows);
    return stats;
  }

  // A big dab (a ball of a hundred voxels changes hundreds of bricks, tens
  // of milliseconds on one core): its bricks are decoded and combined on
  // every core, then stored here in brick order, so the volume, its brick
  // versions and the undo history are what one thread makes. A row of the
  // rotated tool is shared by the bricks along x only: each task takes one
  // such line of bricks, so no two fill the same row at once. Decoded here
  // into buffers of their own: the kept ones are for small dabs.
  std::vector<size_t> lines;  // first job of each line of bricks along x
  for (size_t k = 0; k < jobs.size(); ++k)
    if (k == 0 || jobs[k].b.y != jobs[k - 1].b.y || jobs[k].b.z != jobs[k - 1].b.z)
      lines.push_back(k);
  lines.push_back(jobs.size());
  const size_t brick_bytes = static_cast<size_t>(edge) * edge * edge;
  std::vector<std::vector<uint8_t>> voxels(jobs.size());
  std::vector<Combined> combined(jobs.size());
  struct LineFigures {
    RotatedToolCacheStats rows;
    int64_t decode_ns = 0, apply_ns = 0;
  };
  std::vector<LineFigures> line_figures(lines.size() - 1);
  parallel_for(static_cast<int64_t>(lines.size() - 1), [&](int64_t line) {
    LineFigures& f = line_figures[static_cast<size_t>(line)];
    for (size_t k = lines[static_cast<size_t>(line)]; k < lines[static_cast<size_t>(line) + 1];
         ++k) {
      const int64_t t0 = now_ns();
      voxels[k].resize(brick_bytes + kCombineRowSlack);
      volume_.decode_brick(jobs[k].b, std::span<uint8_t>(voxels[k]).first(brick_bytes));
      const int64_t t1 = now_ns();
      combined[k] = combine_brick(jobs[k].b, jobs[k].bb, voxels[k].data(), f.rows);
      f.decode_ns += t1 - t0;
      f.apply_ns += now_ns() - t1;
    }
  });
  for (const LineFigures& f : line_figures) {
    rows.voxels_requested += f.rows.voxels_requested;
    rows.voxels_reused += f.rows.voxels_reused;
    rows.voxels_rotated += f.rows.voxels_rotated;
    stats.decode_ns += f.decode_ns;
    stats.apply_ns += f.apply_ns;
  }
  cache.add_row_counts(rows);
  stats.bricks_decoded += static_cast<int>(jobs.size());
  const int64_t t_store = now_ns();
  std::vector<Volume::BrickStore> stores;
  for (size_t k = 0; k < jobs.size(); ++k) {
    if (combined[k].changed == 0) continue;
    history_.before_change(volume_, jobs[k].b);
    stores.push_back(
        {jobs[k].b, std::span<uint8_t>(voxels[k]).first(brick_bytes), combined[k].touched});
    ++stats.bricks_changed;
    stats.voxels_changed += combined[k].changed;
  }
  volume_.store_bricks(stores);
  stats.encode_ns += now_ns() - t_store;
  return stats;
}

void Sculptor::external_edit(const Box& region, const std::function<void()>& edit) {
  history_.begin_stroke();
  const Box bricks = volume_.bricks_overlapping(region);
  for (int z = bricks.lo.z; z < bricks.hi.z; ++z)
    for (int y = bricks.lo.y; y < bricks.hi.y; ++y)
      for (int x = bricks.lo.x; x < bricks.hi.x; ++x)
        history_.before_change(volume_, {x, y, z});
  edit();
  history_.end_stroke();
}

}  // namespace sculpt::core
