#include "sculpt/core/mesh/mixed_level_mesh.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstring>
#include <span>
#include <type_traits>
#include <utility>

#include <glm/geometric.hpp>

#include "mesh/march_cells.h"
#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

constexpr glm::ivec3 corner_offset(int k) {
  return {k & 1, (k >> 1) & 1, k >> 2};
}

uint64_t pack_edge(int level, glm::ivec3 lower, int axis) {
  // 19 bits per coordinate (level-0 coordinates up to 2^16, plus margin).
  return (static_cast<uint64_t>(level) << 59) | (static_cast<uint64_t>(axis) << 57) |
         (static_cast<uint64_t>(lower.z + 1) << 38) | (static_cast<uint64_t>(lower.y + 1) << 19) |
         static_cast<uint64_t>(lower.x + 1);
}

// Where rows `now` and `old` of n bytes differ: false when they are equal,
// else true with the first and last byte that differ in [first, last]. Eight
// bytes at a time where n allows (a brick's rows at levels 0 to 2): a big
// dab's update compared its sixty bricks row by row with std::equal and then
// byte by byte, 0.36-0.40 ms of its 3.1-3.3 on two threads.
bool row_difference(const uint8_t* now, const uint8_t* old, int n, int& first, int& last) {
  if constexpr (std::endian::native == std::endian::little) {
    if (n % 8 == 0) {
      first = -1;
      for (int i = 0; i < n; i += 8) {
        uint64_t a, b;
        std::memcpy(&a, now + i, 8);
        std::memcpy(&b, old + i, 8);
        // The lowest byte in memory is the word's least significant one.
        if (const uint64_t d = a ^ b; d != 0) {
          if (first < 0) first = i + std::countr_zero(d) / 8;
          last = i + 7 - std::countl_zero(d) / 8;
        }
      }
      return first >= 0;
    }
  }
  if (std::equal(now, now + n, old)) return false;
  first = 0;
  last = n - 1;
  while (now[first] == old[first])
    ++first;
  while (now[last] == old[last])
    --last;
  return true;
}

// Where a brick's voxels moved, as a box per region of the brick: along each
// axis its first two voxels, its last two and those between, 27 regions.
// A brick beside it reads two of its voxels (at full detail: one for the
// cells' corners, one more for their normals), so it need be meshed again
// only when its region of the brick moved. One box around every moved
// voxel made a big dab's neighbours stale whenever the change reached
// across the brick, whether or not it reached the face they read.
constexpr int kRegions = 27;
using MovedParts = std::array<Box, kRegions>;

class MovedRegions {
 public:
  explicit MovedRegions(int m) : m_(m) {
    lo_.fill(glm::ivec3(m));
    hi_.fill(glm::ivec3(-1));
  }
  // Voxels first..last of row (y, z) moved.
  void add_row(int y, int z, int first, int last) {
    const int ry = region_of(y), rz = region_of(z);
    for (int rx = region_of(first); rx <= region_of(last); ++rx) {
      const int x0 = std::max(first, start(rx)), x1 = std::min(last, start(rx + 1) - 1);
      if (x0 > x1) continue;  // a small brick's empty middle
      const size_t i = static_cast<size_t>((rz * 3 + ry) * 3 + rx);
      lo_[i] = glm::min(lo_[i], glm::ivec3(x0, y, z));
      hi_[i] = glm::max(hi_[i], glm::ivec3(x1, y, z));
    }
  }
  // The regions' boxes in level-0 coordinates, for a brick whose voxel 0 is
  // level-`level` voxel `origin`.
  MovedParts boxes(glm::ivec3 origin, int level) const {
    MovedParts out{};
    for (size_t i = 0; i < out.size(); ++i)
      if (hi_[i].x >= 0) out[i] = Box{(origin + lo_[i]) << level, (origin + hi_[i] + 1) << level};
    return out;
  }

 private:
  // Along an axis: 0 the first two voxels, 2 the last two, 1 between (a
  // brick of four voxels or fewer is all border).
  int region_of(int c) const { return c < 2 ? 0 : (c >= m_ - 2 ? 2 : 1); }
  int start(int region) const {
    return region == 0 ? 0 : region == 1 ? std::min(2, m_) : region == 2 ? std::max(2, m_ - 2) : m_;
  }
  int m_;
  std::array<glm::ivec3, kRegions> lo_, hi_;
};

// The interpolant at level-0 point x of the values at the level-`lambda`
// grid's points around it (value_at(i), i a level-lambda point): bilinear on
// a face of that grid, linear on an edge, the point's own value on a point.
// One function for every caller, so a sample interpolated anywhere is the
// same float to the bit.
template <class ValueAt>
float interpolate(glm::ivec3 x, int lambda, const ValueAt& value_at) {
  const int big = 1 << lambda;
  glm::ivec3 i0;
  glm::vec3 w;
  for (int a = 0; a < 3; ++a) {
    i0[a] = x[a] / big;
    w[a] = static_cast<float>(x[a] - i0[a] * big) / static_cast<float>(big);
  }
  float value = 0.0f;
  for (int c = 0; c < 8; ++c) {
    const glm::ivec3 o = corner_offset(c);
    float weight = 1.0f;
    for (int a = 0; a < 3; ++a)
      weight *= o[a] ? w[a] : 1.0f - w[a];
    if (weight == 0.0f) continue;
    value += weight * value_at(i0 + o);
  }
  return value;
}

}  // namespace

// An open-addressing table: a brick's face needs a few hundred agreed
// samples, each read by up to eight finer points, and a node-based map's
// allocations cost more than the samples.
class MixedLevelMeshCache::SharedMemo {
 public:
  const float* find(uint64_t key) const {
    if (keys_.empty()) return nullptr;
    for (size_t i = slot(key);; i = (i + 1) & (keys_.size() - 1)) {
      if (keys_[i] == key) return &values_[i];
      if (keys_[i] == kEmpty) return nullptr;
    }
  }
  // The level voxels raw() read last (brick index * 8 + level), valid while
  // one brick is meshed: the decoded voxels do not change meanwhile.
  uint64_t raw_key = ~uint64_t{0};
  const uint8_t* raw_voxels = nullptr;

  void insert(uint64_t key, float value) {
    if (2 * (used_ + 1) > keys_.size()) grow();
    size_t i = slot(key);
    while (keys_[i] != kEmpty)
      i = (i + 1) & (keys_.size() - 1);
    keys_[i] = key;
    values_[i] = value;
    ++used_;
  }

 private:
  static constexpr uint64_t kEmpty = ~uint64_t{0};
  size_t slot(uint64_t key) const {
    return static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> 40) & (keys_.size() - 1);
  }
  void grow() {
    std::vector<uint64_t> keys(std::max<size_t>(1024, 2 * keys_.size()), kEmpty);
    std::vector<float> values(keys.size());
    keys.swap(keys_);
    values.swap(values_);
    used_ = 0;
    for (size_t i = 0; i < keys.size(); ++i)
      if (keys[i] != kEmpty) insert(keys[i], values[i]);
  }
  std::vector<uint64_t> keys_;
  std::vector<float> values_;
  size_t used_ = 0;
};

MixedLevelMeshCache::MixedLevelMeshCache(const MarchingCubesOptions& options) : options_(options) {}

bool MixedLevelMeshCache::in_grid(glm::ivec3 b) const {
  return glm::all(glm::greaterThanEqual(b, glm::ivec3(0))) && glm::all(glm::lessThan(b, grid_));
}

const MixedLevelMeshCache::Decoded& MixedLevelMeshCache::decoded(glm::ivec3 b, int k,
                                                                 bool* scratch_used) {
  const int m = edge_ >> k;
  const size_t n = static_cast<size_t>(m) * m * m;
  if (const Brick& brick = volume_->brick(b); brick.is_uniform()) {
    const int key = int{brick.uniform_value()} * 8 + k;
    if (!frozen_) {
      Decoded& u = uniform_[key];
      if (u.voxels.size() != n) u.voxels.assign(n, brick.uniform_value());
      return u;
    }
    if (const auto it = uniform_.find(key); it != uniform_.end() && it->second.voxels.size() == n)
      return it->second;
  }
  const uint64_t key = static_cast<uint64_t>(index(b)) * 8 + static_cast<uint64_t>(k);
  const uint64_t version = volume_->brick_version(b);
  if (frozen_) {
    // Bricks meshed in parallel read what update() decoded for them; the
    // map is not changed while they run. A read that was not foreseen is
    // decoded into this thread's scratch (correct, only slower: counted).
    const auto it = decoded_.find(key);
    if (it != decoded_.end() && it->second.version == version && it->second.voxels.size() == n)
      return it->second;
    thread_local Decoded scratch;
    scratch.voxels.resize(n);
    volume_->decode_brick(b, scratch.voxels, k);
    scratch.version = version;
    unforeseen_decodes_.add();
    if (scratch_used != nullptr) *scratch_used = true;
    return scratch;
  }
  const auto [d, stale] = entry_for(b, k);
  if (stale) {
    volume_->decode_brick(b, d->voxels, k);
    ++decodes_;
  }
  return *d;
}

std::pair<MixedLevelMeshCache::Decoded*, bool> MixedLevelMeshCache::entry_for(glm::ivec3 b, int k) {
  const uint64_t key = static_cast<uint64_t>(index(b)) * 8 + static_cast<uint64_t>(k);
  const auto [entry, added] = decoded_.try_emplace(key);
  if (added) decoded_added_.push_back(key);
  Decoded& d = entry->second;
  const auto m = static_cast<size_t>(edge_ >> k);
  const uint64_t version = volume_->brick_version(b);
  if (d.voxels.size() == m * m * m && d.version == version) return {&d, false};
  d.voxels.resize(m * m * m);
  d.version = version;
  return {&d, true};
}

const uint8_t* MixedLevelMeshCache::decoded_voxels(glm::ivec3 b, int k,
                                                   std::vector<uint8_t>& spare) {
  bool scratch = false;
  const Decoded& d = decoded(b, k, &scratch);
  if (!scratch) return d.voxels.data();
  spare = d.voxels;  // the thread's scratch: the next decode would overwrite it
  return spare.data();
}

float MixedLevelMeshCache::raw(int k, glm::ivec3 p, SharedMemo& memo) {
  const glm::ivec3 d = level_dims_[static_cast<size_t>(k)];
  if (glm::any(glm::lessThan(p, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(p, d)))
    return 0.0f;
  const int shift = std::countr_zero(static_cast<unsigned>(edge_)) - k;
  const int m = 1 << shift;
  const glm::ivec3 b = p >> shift;
  const glm::ivec3 l = p & (m - 1);
  const size_t at = (static_cast<size_t>(l.z) * m + l.y) * m + l.x;
  // A face's samples come from a few bricks in turn: the last one's voxels
  // are kept at hand (a map lookup per sample).
  const uint64_t key = static_cast<uint64_t>(index(b)) * 8 + static_cast<uint64_t>(k);
  if (memo.raw_key == key) return memo.raw_voxels[at];
  std::vector<uint8_t> spare;
  const uint8_t* voxels = decoded_voxels(b, k, spare);
  if (!spare.empty()) return voxels[at];  // not kept: read once
  memo.raw_key = key;
  memo.raw_voxels = voxels;
  return voxels[at];
}

float MixedLevelMeshCache::shared(int k, glm::ivec3 p, SharedMemo& memo) {
  // Points of one coarse square are read by every finer point inside it.
  const uint64_t key = (static_cast<uint64_t>(k) << 60) | (static_cast<uint64_t>(p.z + 1) << 40) |
                       (static_cast<uint64_t>(p.y + 1) << 20) | static_cast<uint64_t>(p.x + 1);
  if (const float* known = memo.find(key)) return *known;
  // A sample exactly at the iso-level puts the crossings of the edges
  // around it on the grid point itself, where the finer side's polyline
  // could end on an edge the coarser side does not have (the symmetric
  // density ramp makes interpolated ties common). Every brick reads this
  // same value, so moving ties just below the level keeps them agreeing.
  const float agreed = tie_moved(shared_value(k, p, memo));
  memo.insert(key, agreed);
  return agreed;
}

float MixedLevelMeshCache::shared_value(int k, glm::ivec3 p, SharedMemo& memo) {
  const glm::ivec3 d = level_dims_[static_cast<size_t>(k)];
  if (glm::any(glm::lessThan(p, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(p, d)))
    return 0.0f;
  const int s = 1 << k;
  const glm::ivec3 x = p * s;  // level-0 position
  const glm::ivec2 range = levels_at(x * 2);
  if (range.y <= k) {
    // On the grid of every brick sharing it: the finest one's voxel. Level-f
    // voxel i stands for the mean of [i 2^f, (i+1) 2^f) but sits at i 2^f,
    // (2^f - 1) / 2 voxels below its centre; the finest level keeps that
    // offset smallest, so no brick sees its face samples lie beyond its own
    // first inner layer (which pinched off bubbles and handles where the
    // surface grazes a face between levels two or more apart).
    const int f = range.x;
    return raw(f, x >> f, memo);
  }
  const int lambda = range.y;
  return interpolate(x, lambda, [&](glm::ivec3 i) { return shared(lambda, i, memo); });
}

glm::ivec2 MixedLevelMeshCache::levels_at(glm::ivec3 x2) const {
  // Brick edges are powers of two: shifts, not divisions (x2 >= 0).
  const int shift = std::countr_zero(static_cast<unsigned>(edge_)) + 1;
  const int below = (2 * edge_) - 1;
  glm::ivec3 lo, hi;
  for (int a = 0; a < 3; ++a) {
    const int b = x2[a] >> shift;
    lo[a] = std::clamp((x2[a] & below) == 0 ? b - 1 : b, 0, grid_[a] - 1);
    hi[a] = std::clamp(b, 0, grid_[a] - 1);
  }
  glm::ivec2 range(100, 0);
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y)
      for (int x = lo.x; x <= hi.x; ++x) {
        const int l = level_of({x, y, z});
        range = glm::ivec2(std::min(range.x, l), std::max(range.y, l));
      }
  return range;
}

int MixedLevelMeshCache::coarsest_level_at(glm::ivec3 x2) const {
  return levels_at(x2).y;
}

bool MixedLevelMeshCache::uniform_around(glm::ivec3 b, int r) const {
  // Outside the volume reads 0, like an empty uniform brick.
  int value = -1;
  for (int dz = -r; dz <= r; ++dz)
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx) {
        const glm::ivec3 nb = b + glm::ivec3(dx, dy, dz);
        int v = 0;
        if (in_grid(nb)) {
          const Brick& brick = volume_->brick(nb);
          if (!brick.is_uniform()) return false;
          v = brick.uniform_value();
        }
        if (value >= 0 && v != value) return false;
        value = v;
      }
  return true;
}

unsigned MixedLevelMeshCache::levels_used_around(glm::ivec3 b) const {
  // The widest reach (two bricks) around: the bricks that may read b.
  unsigned used = 0;
  for (int dz = -2; dz <= 2; ++dz)
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx)
        if (const glm::ivec3 nb = b + glm::ivec3(dx, dy, dz); in_grid(nb))
          used |= 1u << level_of(nb);
  return used;
}

int16_t MixedLevelMeshCache::uniform_value_of(const Brick& brick) {
  return brick.is_uniform() ? static_cast<int16_t>(brick.uniform_value()) : kNotUniform;
}

void MixedLevelMeshCache::mesh_brick(glm::ivec3 b, CachedBrick& cb) {
  const int k = cb.level;
  const int m = edge_ >> k, s = 1 << k;
  const glm::ivec3 origin = b * m;
  const glm::ivec3 ld = level_dims_[static_cast<size_t>(k)];
  const int side = m + 3;
  // With every brick around at this level (the common case: levels change
  // only far from the camera) the samples are the plain voxels, bytes,
  // marched as bytes: a quarter of the block to fill and scan, and the same
  // mesh to the bit (a byte's value is exact as a float, its differences
  // exact as integers). Otherwise boundary samples are interpolated: floats.
  const bool same_level_around =
      std::all_of(cb.levels.begin(), cb.levels.end(), [k](int8_t l) { return l < 0 || l == k; });
  const bool as_bytes = same_level_around && reach(k) == 1;
  // This thread's blocks, kept between bricks.
  thread_local std::vector<uint8_t> bytes;
  thread_local std::vector<float> block;
  const size_t samples = static_cast<size_t>(side) * side * side;
  if (as_bytes)
    bytes.assign(samples, 0);
  else
    block.assign(samples, 0.0f);
  // The decoded voxels of the brick and its neighbours, looked up once (a
  // lookup per row was a tenth of the update).
  // Bricks of fewer than two voxels a side read two bricks away: those
  // look each row up.
  const uint8_t* around[3][3][3] = {};
  std::vector<uint8_t> spare[3][3][3];
  const bool near = reach(k) == 1;
  for (int dz = -1; dz <= 1 && near; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (const glm::ivec3 nb = b + glm::ivec3(dx, dy, dz); in_grid(nb))
          around[dz + 1][dy + 1][dx + 1] = decoded_voxels(nb, k, spare[dz + 1][dy + 1][dx + 1]);
  auto voxels_of = [&](glm::ivec3 nb) {
    if (!near) return decoded(nb, k).voxels.data();
    const glm::ivec3 d = nb - b + 1;
    return around[d.z][d.y][d.x];
  };
  // Plain level-k voxels, row by row, a brick's run at a time: along each
  // axis the samples before the brick (-1) come from the brick before, those
  // after it (m, m + 1) from the brick after. Found by comparisons, not by
  // dividing (three divisions a run, nine a row).
  struct Run {
    int d, from, to;  // neighbour offset, block coordinates [from, to)
  };
  const Run runs[3] = {{-1, -1, 0}, {0, 0, m}, {1, m, m + 2}};
  auto fill_from_around = [&](auto* samples_out) {
    for (const Run& rz : runs)
      for (int z = rz.from; z < rz.to; ++z) {
        if (origin.z + z < 0 || origin.z + z >= ld.z) continue;
        for (const Run& ry : runs)
          for (int y = ry.from; y < ry.to; ++y) {
            if (origin.y + y < 0 || origin.y + y >= ld.y) continue;
            auto* row = samples_out + (static_cast<size_t>(z + 1) * side + (y + 1)) * side + 1;
            const size_t local_row = static_cast<size_t>(z - rz.d * m) * m + (y - ry.d * m);
            for (const Run& rx : runs) {
              const uint8_t* src = around[rz.d + 1][ry.d + 1][rx.d + 1];
              if (src == nullptr) continue;
              const int x0 = std::max(rx.from, -origin.x), x1 = std::min(rx.to, ld.x - origin.x);
              const uint8_t* src_row = src + local_row * m - rx.d * m;
              if constexpr (std::is_same_v<std::remove_cvref_t<decltype(*row)>, uint8_t>) {
                // Bytes to bytes: a copy (the loop's overlap check sent the
                // compiler's vector copy to its byte loop, a third of this
                // function's time).
                if (x0 < x1) std::memcpy(row + x0, src_row + x0, static_cast<size_t>(x1 - x0));
              } else {
                for (int x = x0; x < x1; ++x)
                  row[x] = src_row[x];
              }
            }
          }
      }
  };
  if (as_bytes)
    fill_from_around(bytes.data());
  else if (near)
    fill_from_around(block.data());
  // Bricks of fewer than two voxels a side: any brick around, looked up.
  for (int z = -1; z <= m + 1 && !near; ++z)
    for (int y = -1; y <= m + 1; ++y) {
      const glm::ivec3 p0 = origin + glm::ivec3(-1, y, z);
      float* row = &block[(static_cast<size_t>(z + 1) * side + (y + 1)) * side];
      if (p0.y < 0 || p0.z < 0 || p0.y >= ld.y || p0.z >= ld.z) continue;
      for (int x = std::max(0, p0.x); x < std::min(ld.x, p0.x + side);) {
        const glm::ivec3 nb(x / m, p0.y / m, p0.z / m);
        const int run_end = std::min({ld.x, p0.x + side, (nb.x + 1) * m});
        const uint8_t* src =
            voxels_of(nb) + (static_cast<size_t>(p0.z - nb.z * m) * m + (p0.y - nb.y * m)) * m;
        for (; x < run_end; ++x)
          row[x - p0.x] = src[x - nb.x * m];
      }
    }
  // Face, edge and corner points: the coarsest sharing level's values. With
  // every brick around at this level they are the plain voxels already
  // read, and the sampling that finds the sharing levels was most of the
  // time.
  // The levels of the bricks sharing a boundary point come from the
  // neighbourhood's, kept in cb.levels (outside the grid: -1, not counted).
  const int r = reach(k), width = 2 * r + 1;
  auto neighbour_level = [&](int dx, int dy, int dz) {
    return cb.levels[static_cast<size_t>(((dz + r) * width + (dy + r)) * width + (dx + r))];
  };
  // The brick's boundary in regions, by where each coordinate lies (0: on
  // the low face, 1: inside, 2: on the high face): every point of a region
  // (a face's inside, an edge's, a corner) is shared by the same bricks, so
  // whether its samples are agreed ones is decided once a region, not once
  // a point.
  auto region_of = [m](int c) { return c == 0 ? 0 : (c == m ? 2 : 1); };
  bool agreed[3][3][3] = {};
  int coarser_inside[3][3][3] = {};  // a face inside's coarser level, or -1
  for (int rz = 0; rz < 3 && !same_level_around; ++rz)
    for (int ry = 0; ry < 3; ++ry)
      for (int rx = 0; rx < 3; ++rx) {
        // The bricks sharing the region: offset 0 and, on a face, -1 or +1.
        int finest = k, coarsest = k;
        for (int dz = rz == 0 ? -1 : 0; dz <= (rz == 2 ? 1 : 0); ++dz)
          for (int dy = ry == 0 ? -1 : 0; dy <= (ry == 2 ? 1 : 0); ++dy)
            for (int dx = rx == 0 ? -1 : 0; dx <= (rx == 2 ? 1 : 0); ++dx) {
              const int l = neighbour_level(dx, dy, dz);
              if (l < 0) continue;
              finest = std::min(finest, l);
              coarsest = std::max(coarsest, l);
            }
        agreed[rz][ry][rx] = finest < k || coarsest > k;
        // A face's inside, shared with one coarser brick: its samples are
        // the coarser grid's interpolated, which shared() would find out
        // point by point (levels_at(), the memo) to the same float.
        const bool face_inside = (rz != 1) + (ry != 1) + (rx != 1) == 1;
        coarser_inside[rz][ry][rx] = face_inside && coarsest > k ? coarsest : -1;
      }
  SharedMemo memo;
  const glm::ivec3 level_dims = level_dims_[static_cast<size_t>(k)];
  for (int z = 0; z <= m && !same_level_around; ++z)
    for (int y = 0; y <= m; ++y) {
      const bool yz_face = z == 0 || y == 0 || z == m || y == m;
      const int rz = region_of(z), ry = region_of(y);
      for (int x = 0; x <= m; x += (yz_face ? 1 : m)) {
        const int rx = region_of(x);
        if (!agreed[rz][ry][rx]) continue;
        const glm::ivec3 p = origin + glm::ivec3(x, y, z);
        float& sample = block[(static_cast<size_t>(z + 1) * side + (y + 1)) * side + (x + 1)];
        if (const int lambda = coarser_inside[rz][ry][rx]; lambda >= 0) {
          const bool inside = glm::all(glm::lessThan(p, level_dims));  // p >= 0 here
          sample =
              tie_moved(inside ? interpolate(p * s, lambda,
                                             [&](glm::ivec3 i) { return shared(lambda, i, memo); })
                               : 0.0f);
        } else {
          sample = shared(k, p, memo);
        }
      }
    }
  cb.stats = {};
  auto key = [&](glm::ivec3 p, int axis) -> uint64_t {
    bool seam = false;
    for (int a = 0; a < 3; ++a)
      if (a != axis && (p[a] == 0 || p[a] == m)) seam = true;
    if (!seam) return BrickMesh::kNotSeam;
    const glm::ivec3 x = (origin + p) * s;
    if (same_level_around) return pack_edge(k, x / s, axis);
    glm::ivec3 mid2 = x * 2;
    mid2[axis] += s;
    const int lambda = coarsest_level_at(mid2);
    const int big = 1 << lambda;
    bool on_line = true;
    for (int a = 0; a < 3; ++a)
      if (a != axis && x[a] % big != 0) on_line = false;
    // Sub-edges of one coarse edge share its key: only one of them is
    // crossed, where the coarse edge is.
    if (lambda > k && on_line) return pack_edge(lambda, x / big, axis);
    return pack_edge(k, x / s, axis);
  };
  // A new mesh, not the old one remade: the old one may be held by whoever
  // it was handed to (shared_brick_mesh). Sized as the old one was, the
  // march seldom grows it.
  BrickMesh made;
  if (cb.mesh) {
    made.mesh.positions.reserve(cb.mesh->mesh.positions.size());
    made.mesh.normals.reserve(cb.mesh->mesh.normals.size());
    made.mesh.triangles.reserve(cb.mesh->mesh.triangles.size());
    made.seams.reserve(cb.mesh->seams.size());
  }
  cb.mesh.reset();
  if (as_bytes)
    detail::march_byte_cells(bytes.data(), glm::ivec3(m), origin, k, options_.iso, key, made);
  else
    detail::march_float_cells(block.data(), glm::ivec3(m), origin, k, options_.iso, key, made);
  // No crossing among the corners (the march finds that first, row by
  // row): nothing to stitch either.
  if (made.empty()) return;
  // Only a coarser face neighbour leaves gaps for this brick to close.
  bool coarser_face = false;
  for (int a = 0; a < 3; ++a)
    for (int side_sign : {-1, 1}) {
      glm::ivec3 nb = b;
      nb[a] += side_sign;
      coarser_face = coarser_face || (in_grid(nb) && level_of(nb) > k);
    }
  if (coarser_face) stitch(b, k, made, cb.stats);
  cb.mesh = std::make_shared<const BrickMesh>(std::move(made));
}

void MixedLevelMeshCache::stitch(glm::ivec3 b, int k, BrickMesh& out, MixedLevelStats& st) const {
  Mesh& mesh = out.mesh;
  // Faces toward a coarser neighbour (2 axis + 1 for the high side): only
  // there are gaps for this brick to close.
  const glm::vec3 lo(b * edge_), hi((b + 1) * edge_);
  int coarser_faces = 0;
  for (int face = 0; face < 6; ++face) {
    glm::ivec3 nb = b;
    nb[face / 2] += (face & 1) ? 1 : -1;
    if (in_grid(nb) && level_of(nb) > k) coarser_faces |= 1 << face;
  }
  // Which face planes each vertex lies on: vertices on a face plane have
  // that coordinate exactly (a crossing moves along its edge only).
  std::vector<uint8_t> on_faces(mesh.positions.size(), 0);
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    int faces = 0;
    for (int a = 0; a < 3; ++a) {
      if (mesh.positions[v][a] == lo[a]) faces |= 1 << (2 * a);
      if (mesh.positions[v][a] == hi[a]) faces |= 1 << (2 * a + 1);
    }
    on_faces[v] = static_cast<uint8_t>(faces);
  }
  // Edges in such a face used by one triangle of this brick bound its gaps
  // (an edge in two triangles is inside the surface). Only edges with both
  // ends on one of those planes are counted: a tenth of the mesh's or less.
  auto edge_key = [](uint32_t a, uint32_t c) {
    return (static_cast<uint64_t>(std::min(a, c)) << 32) | std::max(a, c);
  };
  auto in_face = [&](uint32_t a, uint32_t c) {
    return (on_faces[a] & on_faces[c] & coarser_faces) != 0;
  };
  std::vector<uint64_t> face_edges;
  for (const glm::uvec3& t : mesh.triangles)
    for (int c = 0; c < 3; ++c)
      if (in_face(t[c], t[(c + 1) % 3])) face_edges.push_back(edge_key(t[c], t[(c + 1) % 3]));
  if (face_edges.empty()) return;
  std::sort(face_edges.begin(), face_edges.end());
  auto used_once = [&](uint64_t key) {
    const auto [first, last] = std::equal_range(face_edges.begin(), face_edges.end(), key);
    return last - first == 1;
  };
  struct Gap {
    uint64_t group;  // face and coarse square
    uint32_t from, to;
  };
  std::vector<Gap> gaps;
  for (const glm::uvec3& t : mesh.triangles)
    for (int c = 0; c < 3; ++c) {
      const uint32_t from = t[c], to = t[(c + 1) % 3];
      if (!in_face(from, to) || !used_once(edge_key(from, to))) continue;
      // The first face both ends lie on (an edge along a brick's edge lies
      // in two); a same-level face is welded, a finer one is its stitch.
      const int face = std::countr_zero(static_cast<unsigned>(on_faces[from] & on_faces[to]));
      if (((coarser_faces >> face) & 1) == 0) continue;
      const int axis = face / 2;
      glm::ivec3 nb = b;
      nb[axis] += (face & 1) ? 1 : -1;
      const int lambda = level_of(nb);
      // The midpoint in double: in float it would round a vertex one ulp
      // off the plane onto it.
      const glm::dvec3 mid =
          0.5 * (glm::dvec3(mesh.positions[from]) + glm::dvec3(mesh.positions[to]));
      const double big = 1 << lambda;
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const auto su = static_cast<uint64_t>(std::floor(mid[u] / big));
      const auto sv = static_cast<uint64_t>(std::floor(mid[v] / big));
      gaps.push_back({static_cast<uint64_t>(face) | (su << 3) | (sv << 23), from, to});
    }
  std::sort(gaps.begin(), gaps.end(), [](const Gap& a, const Gap& c) {
    return a.group != c.group ? a.group < c.group : a.from < c.from;
  });

  // Fans the loop (a polyline closed by its chord) from its centroid, each
  // triangle walking the loop backwards, so every loop edge ends up in two
  // triangles.
  std::vector<uint32_t> loop;
  auto fill = [&] {
    if (loop.size() < 3) return;  // one segment: the coarse side's own edge
    ++st.stitch_loops;
    glm::vec3 centre(0.0f), normal(0.0f);
    for (uint32_t v : loop) {
      centre += mesh.positions[v];
      normal += mesh.normals[v];
    }
    const auto c = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.push_back(centre / static_cast<float>(loop.size()));
    const float len = glm::length(normal);
    mesh.normals.push_back(len > 0.0f ? normal / len : mesh.normals[loop[0]]);
    for (size_t i = 0; i < loop.size(); ++i) {
      mesh.triangles.emplace_back(c, loop[(i + 1) % loop.size()], loop[i]);
      ++st.stitch_triangles;
    }
  };
  std::vector<uint8_t> done;
  for (size_t g0 = 0; g0 < gaps.size();) {
    size_t g1 = g0;
    while (g1 < gaps.size() && gaps[g1].group == gaps[g0].group)
      ++g1;
    const std::span<const Gap> group(&gaps[g0], g1 - g0);
    done.assign(group.size(), 0);
    auto next_from = [&](uint32_t v) -> int {
      for (size_t i = 0; i < group.size(); ++i)
        if (!done[i] && group[i].from == v) return static_cast<int>(i);
      return -1;
    };
    auto walk = [&](size_t first) {
      loop.clear();
      loop.push_back(group[first].from);
      for (int i = static_cast<int>(first); i >= 0;
           i = next_from(group[static_cast<size_t>(i)].to)) {
        done[static_cast<size_t>(i)] = 1;
        if (group[static_cast<size_t>(i)].to == loop.front()) break;  // a closed loop
        loop.push_back(group[static_cast<size_t>(i)].to);
      }
    };
    // Polylines, from their starts (no gap edge ends there). Each is closed
    // by the coarser brick's segment between its ends: inside one coarse
    // square both sides see the same bilinear interpolant, whose sample
    // arithmetic is exact (dyadic weights times bytes), so the asymptotic
    // decider pairs the crossings the same way on both.
    for (size_t i = 0; i < group.size(); ++i) {
      bool start = true;
      for (const Gap& g : group)
        if (g.to == group[i].from) start = false;
      if (start && !done[i]) {
        walk(i);
        fill();
      }
    }
    // Closed loops: a contour inside one coarse square, which the coarser
    // brick does not see at all.
    for (size_t i = 0; i < group.size(); ++i)
      if (!done[i]) {
        walk(i);
        fill();
      }
    g0 = g1;
  }
}

MeshUpdate MixedLevelMeshCache::update(const Volume& volume, std::span<const int> brick_levels,
                                       StoredVoxelsByBrick* stored) {
  assert(static_cast<int64_t>(brick_levels.size()) == volume.brick_count());
  const bool reset = volume_ != &volume || volume.dims() != dims_ || volume.brick_grid() != grid_ ||
                     volume.brick_edge() != edge_;
  if (reset) {
    volume_ = &volume;
    dims_ = volume.dims();
    grid_ = volume.brick_grid();
    edge_ = volume.brick_edge();
    // Mesh versions keep counting across a reset, so a renderer's stamps
    // never match a mesh of the previous volume.
    uint64_t versions = 0;
    for (const CachedBrick& cb : bricks_)
      versions = std::max(versions, cb.mesh_version);
    bricks_.assign(static_cast<size_t>(volume.brick_count()), CachedBrick{});
    kept_bytes_ = 0;
    for (CachedBrick& cb : bricks_)
      cb.mesh_version = versions;
    seen_versions_.assign(static_cast<size_t>(volume.brick_count()), 0);
    seen_uniform_.assign(static_cast<size_t>(volume.brick_count()), kNotUniform);
    for (size_t i = 0; i < seen_versions_.size(); ++i) {
      const glm::ivec3 b = grid_position(static_cast<int64_t>(i), grid_);
      seen_versions_[i] = volume.brick_version(b);
      seen_uniform_[i] = uniform_value_of(volume.brick(b));
    }
    decoded_.clear();
    decoded_added_.clear();
  }
  // A new volume, or levels other than the last update's: every brick's
  // neighbourhood is looked at, not only the changed bricks'.
  const bool levels_moved = reset || !std::equal(levels_.begin(), levels_.end(),
                                                 brick_levels.begin(), brick_levels.end());
  levels_.assign(brick_levels.begin(), brick_levels.end());
  for (int k = 0; k <= volume.levels(); ++k)
    level_dims_[static_cast<size_t>(k)] = volume.level_dims(k);
  for ([[maybe_unused]] int l : levels_)
    assert(l >= 0 && l <= volume.levels());
  decodes_ = 0;
  MeshUpdate stats;
  // Where stored bricks changed (level-0 boxes), at every level some brick
  // reads them: their kept decoded voxels before and after. A brick with
  // nothing kept sat among uniform bricks, which were not meshed (nothing
  // was read): its whole box counts as changed. Each box with the index of
  // the brick it lies in, sorted by it once found (boxes_in()).
  std::vector<std::pair<int64_t, Box>> changed;
  std::vector<glm::ivec3> version_moved;
  // Each kept decode of a moved brick, decoded again and compared, in
  // parallel (a big dab moves sixty bricks: 2.4 ms on one thread). Each
  // job writes only its own map entry, which is already there.
  struct Redecode {
    glm::ivec3 brick;
    int level;
    Decoded* kept;
    // Where voxels moved (level-0 boxes; empty: nothing differs), one box
    // per region of the brick: a face's, edge's or corner's two-voxel
    // border, or the inside (MovedParts).
    MovedParts moved = {};
    StoredVoxels* given = nullptr;  // its level-0 voxels, to take
    bool compared_where_changed = false;
  };
  std::vector<Redecode> redecodes;
  // Brick n's level-0 voxels as given in `stored`, or null.
  auto given_voxels = [&](glm::ivec3 n) -> StoredVoxels* {
    if (stored == nullptr) return nullptr;
    const auto it = stored->find(static_cast<int64_t>(index(n)));
    if (it == stored->end() || it->second.version != volume.brick_version(n)) return nullptr;
    if (it->second.voxels.size() != static_cast<size_t>(edge_) * edge_ * edge_) return nullptr;
    return &it->second;
  };
  for (int z = 0; z < grid_.z; ++z)
    for (int y = 0; y < grid_.y; ++y)
      for (int x = 0; x < grid_.x; ++x) {
        const glm::ivec3 n(x, y, z);
        uint64_t& seen = seen_versions_[index(n)];
        if (seen == volume.brick_version(n)) continue;
        seen = volume.brick_version(n);
        version_moved.push_back(n);
        const int16_t was_uniform =
            std::exchange(seen_uniform_[index(n)], uniform_value_of(volume.brick(n)));
        bool kept = false;
        for (int k = 0; k <= volume.levels(); ++k) {
          auto it = decoded_.find(static_cast<uint64_t>(index(n)) * 8 + static_cast<uint64_t>(k));
          if (it == decoded_.end()) continue;
          kept = true;
          redecodes.push_back({n, k, &it->second, {}, k == 0 ? given_voxels(n) : nullptr});
        }
        if (kept) continue;
        // Nothing kept: it sat among uniform bricks, unmeshed. When it was
        // uniform itself, its old voxels are known all the same: compared
        // with them, only the part that moved counts as changed (a big
        // ball added in the air moved 92 bricks; their whole boxes made
        // 304 bricks stale, the voxels that changed 142). Decoded at the
        // levels the bricks around it mesh at, which they read anyway.
        if (was_uniform == kNotUniform) {
          changed.emplace_back(static_cast<int64_t>(index(n)), Box{n * edge_, (n + 1) * edge_});
          continue;
        }
        const unsigned used = levels_used_around(n);
        for (int k = 0; k <= volume.levels(); ++k) {
          if (!(used & (1u << k))) continue;
          const uint64_t key = static_cast<uint64_t>(index(n)) * 8 + static_cast<uint64_t>(k);
          const auto [entry, added] = decoded_.try_emplace(key);
          if (added) decoded_added_.push_back(key);
          Decoded& old = entry->second;
          const size_t m = static_cast<size_t>(edge_ >> k);
          old.voxels.assign(m * m * m, static_cast<uint8_t>(was_uniform));
          redecodes.push_back({n, k, &old, {}, k == 0 ? given_voxels(n) : nullptr});
        }
      }
  parallel_for(
      static_cast<int64_t>(redecodes.size()),
      [&](int64_t i) {
        Redecode& r = redecodes[static_cast<size_t>(i)];
        const int m = edge_ >> r.level;
        thread_local std::vector<uint8_t> old;
        old.swap(r.kept->voxels);
        std::vector<uint8_t>& now = r.kept->voxels;
        // The rows to compare: all, or where the sculptor says the voxels
        // changed since the version kept (outside they are the same).
        Box rows{glm::ivec3(0), glm::ivec3(m)};
        if (r.given != nullptr) {
          now.swap(r.given->voxels);  // what decoding would give, to the byte
          if (r.given->changed_from == r.kept->version) {
            rows = intersect(
                Box{r.given->changed.lo - r.brick * edge_, r.given->changed.hi - r.brick * edge_},
                rows);
            r.compared_where_changed = true;
          }
        } else {
          now.resize(static_cast<size_t>(m) * m * m);
          volume.decode_brick(r.brick, now, r.level);
        }
        r.kept->version = volume.brick_version(r.brick);
        if (old.size() != now.size()) {
          r.moved[0] = Box{r.brick * edge_, (r.brick + 1) * edge_};
          return;
        }
        MovedRegions regions(m);
        for (int vz = rows.lo.z; vz < rows.hi.z; ++vz)
          for (int vy = rows.lo.y; vy < rows.hi.y; ++vy) {
            const size_t row = (static_cast<size_t>(vz) * m + vy) * m;
            // The row's first and last voxel that moved bound it: a compare
            // and a box update per voxel was a twentieth of the update.
            int first = 0, last = 0;
            if (!row_difference(&now[row], &old[row], m, first, last)) continue;
            regions.add_row(vy, vz, first, last);
          }
        r.moved = regions.boxes(r.brick * m, r.level);
      },
      options_.threads);
  decodes_ += static_cast<int64_t>(redecodes.size());
  for (const Redecode& r : redecodes) {
    for (const Box& part : r.moved)
      if (!part.empty()) changed.emplace_back(static_cast<int64_t>(index(r.brick)), part);
    if (r.given == nullptr) continue;
    ++stats.bricks_given;
    stats.bricks_compared_where_changed += r.compared_where_changed ? 1 : 0;
    stored->erase(static_cast<int64_t>(index(r.brick)));  // taken: what is left is not its voxels
  }
  std::sort(changed.begin(), changed.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  // The boxes where brick i's voxels moved.
  auto boxes_in = [&](int64_t i) {
    const auto first = std::lower_bound(changed.begin(), changed.end(), i,
                                        [](const auto& c, int64_t j) { return c.first < j; });
    auto last = first;
    while (last != changed.end() && last->first == i)
      ++last;
    return std::span(first, last);
  };
  // Meshes kept from other levels may read voxels of levels no longer
  // decoded, so `changed` cannot vouch for them: every brick that could read
  // a brick whose version moved drops its kept meshes.
  const int widest_margin = 2 << volume.levels();
  for (glm::ivec3 n : version_moved) {
    const Box around =
        volume.bricks_overlapping(Box{n * edge_ - widest_margin, (n + 1) * edge_ + widest_margin});
    for (int z = around.lo.z; z < around.hi.z; ++z)
      for (int y = around.lo.y; y < around.hi.y; ++y)
        for (int x = around.lo.x; x < around.hi.x; ++x)
          drop_kept_meshes(bricks_[index({x, y, z})]);
  }
  std::vector<int8_t> levels;
  std::vector<glm::ivec3> stale_bricks;
  std::vector<glm::ivec3> reused_bricks;
  // The voxels brick b reads: its box, one level-k voxel below and two
  // above (normals), face samples from voxels on its boundary.
  auto reads_of = [&](glm::ivec3 b) {
    const int margin = 2 << level_of(b);
    return Box{b * edge_ - margin, (b + 1) * edge_ + margin};
  };
  auto changed_within = [&](std::span<const std::pair<int64_t, Box>> boxes, const Box& reads) {
    return std::any_of(boxes.begin(), boxes.end(),
                       [&](const auto& c) { return !intersect(c.second, reads).empty(); });
  };
  // Brick b, whose reads hold voxels that moved when `reads_changed`.
  auto consider = [&](glm::ivec3 b, bool reads_changed) {
    CachedBrick& cb = bricks_[index(b)];
    const int k = level_of(b);
    const int r = reach(k);
    levels.clear();
    for (int dz = -r; dz <= r; ++dz)
      for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
          const glm::ivec3 nb = b + glm::ivec3(dx, dy, dz);
          levels.push_back(static_cast<int8_t>(in_grid(nb) ? level_of(nb) : -1));
        }
    const bool levels_moved_here = cb.level != k || cb.levels != levels;
    if (!levels_moved_here && !reads_changed) return;
    ++stats.bricks_changed;
    const bool had_mesh = cb.mesh != nullptr;
    // Only its level or its neighbours' moved: its mesh stays right for
    // the levels it was made at, so it is kept for when they come back.
    if (!reads_changed && cb.level >= 0) keep_mesh(cb);
    cb.level = k;
    cb.levels.assign(levels.begin(), levels.end());
    if (uniform_around(b, r)) {
      // No crossing anywhere it reads: no surface, nothing to decode.
      if (had_mesh) ++cb.mesh_version;
      cb.mesh.reset();
      cb.stats = {};
      return;
    }
    if (!reads_changed && take_kept_mesh(cb)) {
      ++cb.mesh_version;
      ++stats.bricks_reused;
      reused_bricks.push_back(b);
      return;
    }
    stale_bricks.push_back(b);
  };
  // Whether brick b's reads hold a voxel that moved: the boxes of each
  // brick they overlap, looked at.
  auto reads_hold_a_change = [&](glm::ivec3 b) {
    const Box reads = reads_of(b);
    const Box read_bricks = volume.bricks_overlapping(reads);
    for (int z = read_bricks.lo.z; z < read_bricks.hi.z; ++z)
      for (int y = read_bricks.lo.y; y < read_bricks.hi.y; ++y)
        for (int x = read_bricks.lo.x; x < read_bricks.hi.x; ++x)
          if (changed_within(boxes_in(static_cast<int64_t>(index({x, y, z}))), reads)) return true;
    return false;
  };
  if (levels_moved) {
    for (int z = 0; z < grid_.z; ++z)
      for (int y = 0; y < grid_.y; ++y)
        for (int x = 0; x < grid_.x; ++x)
          consider({x, y, z}, reads_hold_a_change({x, y, z}));
  } else {
    // Levels as before: only a brick whose reads hold a moved voxel can be
    // stale (a big volume has tens of thousands of bricks; a dab changes a
    // few). They are found from each moved brick's boxes: of the bricks
    // within the farthest any brick reads (the coarsest level in use), those
    // whose own reads, at their level, reach one. (Every brick within the
    // widest level's margin, 64 voxels, looked at whole: 300-370 bricks for
    // a big dab's 60-110 stale ones, 0.3-0.4 ms on one thread.)
    const int farthest_read = 2 << *std::max_element(levels_.begin(), levels_.end());
    std::vector<int64_t> near;
    for (auto group = changed.begin(); group != changed.end();) {
      // One moved brick's boxes: `changed` is sorted by brick.
      const auto group_end = std::find_if(group, changed.end(),
                                          [&](const auto& c) { return c.first != group->first; });
      const std::span boxes(group, group_end);
      group = group_end;
      Box all = boxes.front().second;
      for (const auto& [i, box] : boxes)
        all = hull(all, box);
      const Box around =
          volume.bricks_overlapping(Box{all.lo - farthest_read, all.hi + farthest_read});
      for (int z = around.lo.z; z < around.hi.z; ++z)
        for (int y = around.lo.y; y < around.hi.y; ++y)
          for (int x = around.lo.x; x < around.hi.x; ++x)
            if (changed_within(boxes, reads_of({x, y, z})))
              near.push_back(static_cast<int64_t>(index({x, y, z})));
    }
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());
    for (int64_t i : near)
      consider(grid_position(i, grid_), /*reads_changed=*/true);
  }
  // Decode what the stale bricks read (their neighbourhood, at every level
  // found in it), then mesh them in parallel: each writes only its own
  // cached brick and reads the decoded voxels, which stay as they are. A
  // reused mesh's reads are decoded too: the next edit finds what changed
  // under it by comparing them. A uniform brick is read from its value's
  // one buffer. The decodes share the cores: each writes only its own
  // entry, made (and marked current) here first, and the map's entries stay
  // where they are as it grows.
  struct Decode {
    glm::ivec3 brick;
    int level;
    Decoded* entry;
    StoredVoxels* given = nullptr;  // its level-0 voxels, to take
  };
  std::vector<Decode> neighbourhood_decodes;
  std::vector<glm::ivec3> to_decode = stale_bricks;
  to_decode.insert(to_decode.end(), reused_bricks.begin(), reused_bricks.end());
  for (glm::ivec3 b : to_decode) {
    const int k = level_of(b);
    const int r = reach(k);
    uint8_t used = static_cast<uint8_t>(1u << k);
    for (int dz = -r; dz <= r; ++dz)
      for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx)
          if (const glm::ivec3 nb = b + glm::ivec3(dx, dy, dz); in_grid(nb))
            used = static_cast<uint8_t>(used | (1u << level_of(nb)));
    for (int dz = -r; dz <= r; ++dz)
      for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
          const glm::ivec3 nb = b + glm::ivec3(dx, dy, dz);
          if (!in_grid(nb)) continue;
          for (int l = 0; l <= volume.levels(); ++l) {
            if (!(used & (1u << l))) continue;
            if (volume.brick(nb).is_uniform()) {
              (void)decoded(nb, l);  // its value's one buffer, made once
              continue;
            }
            if (const auto [d, stale] = entry_for(nb, l); stale)
              neighbourhood_decodes.push_back({nb, l, d, l == 0 ? given_voxels(nb) : nullptr});
          }
        }
  }
  parallel_for(
      static_cast<int64_t>(neighbourhood_decodes.size()),
      [&](int64_t i) {
        const Decode& d = neighbourhood_decodes[static_cast<size_t>(i)];
        if (d.given != nullptr) {
          d.entry->voxels.swap(d.given->voxels);
        } else {
          volume.decode_brick(d.brick, d.entry->voxels, d.level);
        }
      },
      options_.threads);
  decodes_ += static_cast<int64_t>(neighbourhood_decodes.size());
  for (const Decode& d : neighbourhood_decodes) {
    if (d.given == nullptr) continue;
    ++stats.bricks_given;
    stored->erase(static_cast<int64_t>(index(d.brick)));
  }
  frozen_ = true;
  parallel_for(
      static_cast<int64_t>(stale_bricks.size()),
      [&](int64_t i) {
        if (cancelled_ && cancelled_()) return;
        const glm::ivec3 b = stale_bricks[static_cast<size_t>(i)];
        CachedBrick& cb = bricks_[index(b)];
        mesh_brick(b, cb);
        ++cb.mesh_version;
      },
      options_.threads);
  frozen_ = false;
  for (glm::ivec3 b : stale_bricks)
    stats.bricks_meshed += bricks_[index(b)].mesh ? 1 : 0;
  // Forget decoded bricks at levels no brick around them uses any more.
  // Only a move of the levels can leave a kept entry unused; with the levels
  // as before, only the entries added since the last sweep are looked at
  // (the whole map, every brick's neighbourhood, took 0.2 ms of each small
  // change on the 512^3 bust).
  auto unused = [&](uint64_t key) {
    const size_t i = static_cast<size_t>(key / 8);
    const int k = static_cast<int>(key % 8);
    const glm::ivec3 b(
        static_cast<int>(i % static_cast<size_t>(grid_.x)),
        static_cast<int>((i / static_cast<size_t>(grid_.x)) % static_cast<size_t>(grid_.y)),
        static_cast<int>(i / (static_cast<size_t>(grid_.x) * grid_.y)));
    for (int dz = -2; dz <= 2; ++dz)
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          const glm::ivec3 nb = b + glm::ivec3(dx, dy, dz);
          if (in_grid(nb) && level_of(nb) <= k) return false;
        }
    return true;
  };
  if (levels_moved) {
    std::erase_if(decoded_, [&](const auto& entry) { return unused(entry.first); });
  } else {
    for (uint64_t key : decoded_added_)
      if (unused(key)) decoded_.erase(key);
  }
  decoded_added_.clear();
  trim_kept_meshes();
  stats.bricks_decoded = decodes_;
  return stats;
}

namespace {

size_t mesh_bytes(const std::shared_ptr<const BrickMesh>& shared) {
  if (!shared) return 0;
  const BrickMesh& m = *shared;
  return m.mesh.positions.capacity() * sizeof(m.mesh.positions[0]) +
         m.mesh.normals.capacity() * sizeof(m.mesh.normals[0]) +
         m.mesh.triangles.capacity() * sizeof(m.mesh.triangles[0]) +
         m.seams.capacity() * sizeof(m.seams[0]);
}

}  // namespace

void MixedLevelMeshCache::keep_mesh(CachedBrick& cb) {
  if (kept_budget_bytes_ == 0) return;
  LevelMesh& kept = cb.kept.emplace_back();
  kept.level = cb.level;
  kept.levels = cb.levels;
  kept.mesh = std::move(cb.mesh);
  kept.stats = cb.stats;
  kept.kept_order = kept_count_++;
  kept_bytes_ += mesh_bytes(kept.mesh);
  cb.mesh = {};
}

bool MixedLevelMeshCache::take_kept_mesh(CachedBrick& cb) {
  const auto it = std::find_if(cb.kept.begin(), cb.kept.end(), [&](const LevelMesh& kept) {
    return kept.level == cb.level && kept.levels == cb.levels;
  });
  if (it == cb.kept.end()) return false;
  kept_bytes_ -= mesh_bytes(it->mesh);
  cb.mesh = std::move(it->mesh);
  cb.stats = it->stats;
  cb.kept.erase(it);
  return true;
}

void MixedLevelMeshCache::drop_kept_meshes(CachedBrick& cb) {
  for (const LevelMesh& kept : cb.kept)
    kept_bytes_ -= mesh_bytes(kept.mesh);
  cb.kept.clear();
}

void MixedLevelMeshCache::trim_kept_meshes() {
  if (kept_bytes_ <= kept_budget_bytes_) return;
  // The order in which meshes were kept, oldest first, with their sizes:
  // drop the oldest until what is left fits.
  std::vector<std::pair<uint64_t, size_t>> order_bytes;
  for (const CachedBrick& cb : bricks_)
    for (const LevelMesh& kept : cb.kept)
      order_bytes.emplace_back(kept.kept_order, mesh_bytes(kept.mesh));
  std::sort(order_bytes.begin(), order_bytes.end());
  size_t left = kept_bytes_;
  uint64_t keep_from = 0;
  for (const auto& [order, bytes] : order_bytes) {
    if (left <= kept_budget_bytes_) break;
    left -= bytes;
    keep_from = order + 1;
  }
  for (CachedBrick& cb : bricks_)
    std::erase_if(cb.kept, [&](const LevelMesh& kept) { return kept.kept_order < keep_from; });
  kept_bytes_ = left;
}

const BrickMesh& MixedLevelMeshCache::no_mesh() {
  static const BrickMesh empty;
  return empty;
}

std::shared_ptr<const BrickMesh> MixedLevelMeshCache::shared_brick_mesh(glm::ivec3 b) const {
  static const auto empty = std::make_shared<const BrickMesh>();
  const std::shared_ptr<const BrickMesh>& mesh = bricks_[index(b)].mesh;
  return mesh ? mesh : empty;
}

MixedLevelStats MixedLevelMeshCache::stats() const {
  MixedLevelStats st;
  for (const CachedBrick& cb : bricks_)
    st += cb.stats;
  return st;
}

int64_t MixedLevelMeshCache::triangle_count() const {
  int64_t n = 0;
  for (const CachedBrick& cb : bricks_)
    n += cb.mesh ? static_cast<int64_t>(cb.mesh->mesh.triangles.size()) : 0;
  return n;
}

Mesh MixedLevelMeshCache::welded_mesh() const {
  std::vector<const BrickMesh*> meshes;
  meshes.reserve(bricks_.size());
  for (const CachedBrick& cb : bricks_)
    if (cb.mesh) meshes.push_back(cb.mesh.get());
  return weld_brick_meshes(meshes);
}

Mesh mixed_level_mesh(const Volume& volume, std::span<const int> brick_levels,
                      const MarchingCubesOptions& options, MixedLevelStats* stats) {
  MixedLevelMeshCache cache(options);
  cache.update(volume, brick_levels);
  if (stats) *stats = cache.stats();
  return cache.welded_mesh();
}

}  // namespace sculpt::core
