#include "sculpt/core/sculpt/sculptor.h"
#include "sculpt/core/grid/grid_index.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>

#include "sculpt/core/sculpt/combine_row.h"

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

inline uint64_t load_u64(const uint8_t* p) {
  uint64_t v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

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

DabStats Sculptor::dab(const Dab& dab) {
  assert(tool_ && "Sculptor::dab(): set_tool() first");
  const bool own_stroke = !history_.in_stroke();
  if (own_stroke) history_.begin_stroke();
  DabStats stats = apply(*cache_, dab);
  if (mirror_) {
    const int a = mirror_->axis;
    auto& mc = mirror_caches_[a];
    if (!mc) {
      mc = std::make_unique<RotatedToolCache>(
          std::make_shared<const PreparedTool>(mirror_tool(*tool_, a)), options_.sampling,
          options_.cache_max_bytes, options_.subvoxel_steps);
    }
    Dab m = dab;
    m.position_vox[a] = 2.0f * mirror_->centre_vox - dab.position_vox[a];
    // Reflection M turns rotation R into M R M: the rotation about the
    // reflected axis by the opposite angle, i.e. the quaternion's vector
    // components off the mirror axis change sign.
    glm::quat q = dab.orientation;
    for (int i = 0; i < 3; ++i)
      if (i != a) q[i] = -q[i];  // glm::quat indexes x, y, z, w
    m.orientation = q;
    stats += apply(*mc, m);
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

        const int64_t t0 = now_ns();
        DecodedBrick& decoded = decoded_brick(b, stats);
        std::span<uint8_t> voxels = decoded.brick();
        const int64_t t1 = now_ns();
        const glm::ivec3 origin = b * edge;
        int64_t changed = 0;
        // Bounding box of the rows that changed: only the wavelet
        // coefficients over it are re-encoded.
        Box touched{glm::ivec3(std::numeric_limits<int>::max()),
                    glm::ivec3(std::numeric_limits<int>::min())};
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
            uint8_t* m =
                &voxels[(static_cast<size_t>(z - origin.z) * edge + (y - origin.y)) * edge +
                        (xa - origin.x)];
            // Contact: rotate only where the material can change.
            int c0 = 0, c1 = xb - xa;
            if (saturated >= 0) {
              // Eight voxels at a time through the saturated stretches.
              const uint64_t word = 0x0101010101010101ull * static_cast<uint64_t>(saturated);
              while (c0 + 8 <= c1 && load_u64(m + c0) == word)
                c0 += 8;
              while (c0 < c1 && m[c0] == saturated)
                ++c0;
              while (c1 - 8 >= c0 && load_u64(m + c1 - 8) == word)
                c1 -= 8;
              while (c1 > c0 && m[c1 - 1] == saturated)
                --c1;
            }
            if (c0 >= c1) continue;
            const uint8_t* f =
                entry.row(y - anchor.y, z - anchor.z, xa + c0 - anchor.x, xa + c1 - anchor.x);
            const int64_t row_changed = dab.mode == SculptMode::kSmooth
                                            ? smooth_row(m + c0, f, c1 - c0, strength_q, before,
                                                         glm::ivec3(xa + c0, y, z) - before_box.lo)
                                            : combine_row(dab.mode, m + c0, f, c1 - c0, strength_q);
            if (row_changed != 0) {
              changed += row_changed;
              touched.lo = glm::min(touched.lo, glm::ivec3(xa + c0, y, z));
              touched.hi = glm::max(touched.hi, glm::ivec3(xa + c1, y + 1, z + 1));
            }
          }
        }
        const int64_t t2 = now_ns();
        stats.decode_ns += t1 - t0;
        stats.apply_ns += t2 - t1;
        if (changed == 0) continue;
        history_.before_change(volume_, b);
        volume_.store_brick(b, voxels, touched);  // re-pads `voxels` as stored
        decoded.version = volume_.brick_version(b);
        stats.encode_ns += now_ns() - t2;
        ++stats.bricks_changed;
        stats.voxels_changed += changed;
      }
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
