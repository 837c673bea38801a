#include "sculpt/core/volume/volume.h"

#include <algorithm>
#include <cassert>
#include <cstring>
#include <string>

#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

std::string dims_text(glm::ivec3 d) {
  return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
}

int ceil_div(int a, int b) {
  return (a + b - 1) / b;
}

// Per-thread brick buffer, so whole-volume loops allocate once per thread.
std::span<uint8_t> brick_buffer(int edge) {
  thread_local std::vector<uint8_t> buffer;
  const size_t size = static_cast<size_t>(edge) * edge * edge;
  if (buffer.size() < size) buffer.resize(size);
  return {buffer.data(), size};
}

// Copies the part of `src` (a cube of edge m at cube_origin, x fastest) that
// lies in `clip` into `dst` (a dense grid whose first voxel is dst_origin).
// `clip` keeps a border brick's padding out of the result.
void copy_cube_into(std::span<const uint8_t> src, int m, glm::ivec3 cube_origin,
                    DenseGrid<uint8_t>& dst, glm::ivec3 dst_origin, const Box& clip) {
  const Box overlap = intersect(Box{cube_origin, cube_origin + glm::ivec3(m)}, clip);
  if (overlap.empty()) return;
  const int run = overlap.hi.x - overlap.lo.x;
  for (int z = overlap.lo.z; z < overlap.hi.z; ++z) {
    for (int y = overlap.lo.y; y < overlap.hi.y; ++y) {
      const uint8_t* from =
          &src[(static_cast<size_t>(z - cube_origin.z) * m + (y - cube_origin.y)) * m +
               (overlap.lo.x - cube_origin.x)];
      const glm::ivec3 d = glm::ivec3(overlap.lo.x, y, z) - dst_origin;
      std::memcpy(&dst.at(d.x, d.y, d.z), from, static_cast<size_t>(run));
    }
  }
}

}  // namespace

Status Volume::validate(glm::ivec3 dims, const VolumeOptions& options) {
  if (dims.x < 1 || dims.y < 1 || dims.z < 1 || dims.x > kMaxEdge || dims.y > kMaxEdge ||
      dims.z > kMaxEdge) {
    return Error("volume size " + dims_text(dims) + " is out of range (each edge 1.." +
                 std::to_string(kMaxEdge) + ")");
  }
  if (voxel_count(dims) > kMaxVoxels) {
    return Error("volume size " + dims_text(dims) + " has too many voxels (limit " +
                 std::to_string(kMaxVoxels) + ")");
  }
  if (!is_power_of_two(options.brick_edge) || options.brick_edge < 2 ||
      options.brick_edge > WaveletPyramid::kMaxEdge) {
    return Error("brick edge " + std::to_string(options.brick_edge) +
                 " must be a power of two in 2.." + std::to_string(WaveletPyramid::kMaxEdge));
  }
  if (options.levels < 0 || options.levels > log2_exact(options.brick_edge)) {
    return Error(std::to_string(options.levels) + " levels do not fit a brick of edge " +
                 std::to_string(options.brick_edge) + " (at most " +
                 std::to_string(log2_exact(options.brick_edge)) + ")");
  }
  return {};
}

Volume::Volume(glm::ivec3 dims, uint8_t fill, const VolumeOptions& options)
    : dims_(dims), options_(options) {
  assert(validate(dims, options).ok());
  const int e = options.brick_edge;
  grid_ = {ceil_div(dims.x, e), ceil_div(dims.y, e), ceil_div(dims.z, e)};
  const auto count = static_cast<size_t>(voxel_count(grid_));
  bricks_.assign(count, Brick(fill));
  versions_.assign(count, 0);
  dirty_flags_.assign(count, 0);
}

glm::ivec3 Volume::level_dims(int level) const {
  const int s = 1 << level;
  return {ceil_div(dims_.x, s), ceil_div(dims_.y, s), ceil_div(dims_.z, s)};
}

Box Volume::brick_box(glm::ivec3 b) const {
  const glm::ivec3 lo = b * options_.brick_edge;
  return Box{lo, glm::min(lo + glm::ivec3(options_.brick_edge), dims_)};
}

Box Volume::bricks_overlapping(const Box& region) const {
  const Box clipped = intersect(region, Box{glm::ivec3(0), dims_});
  if (clipped.empty()) return {};
  const int e = options_.brick_edge;
  return Box{clipped.lo / e, (clipped.hi - 1) / e + 1};
}

void Volume::pad_outside(glm::ivec3 b, std::span<uint8_t> voxels) const {
  const int e = options_.brick_edge;
  const glm::ivec3 valid = brick_box(b).size();
  if (valid == glm::ivec3(e)) return;
  for (int z = 0; z < valid.z; ++z) {
    for (int y = 0; y < valid.y; ++y) {
      uint8_t* row = &voxels[(static_cast<size_t>(z) * e + y) * e];
      std::fill(row + valid.x, row + e, row[valid.x - 1]);
    }
    for (int y = valid.y; y < e; ++y) {
      std::memcpy(&voxels[(static_cast<size_t>(z) * e + y) * e],
                  &voxels[(static_cast<size_t>(z) * e + valid.y - 1) * e], static_cast<size_t>(e));
    }
  }
  const size_t slice = static_cast<size_t>(e) * e;
  for (int z = valid.z; z < e; ++z) {
    std::memcpy(&voxels[z * slice], &voxels[(valid.z - 1) * slice], slice);
  }
}

Volume Volume::from_bricks(glm::ivec3 dims, const VolumeOptions& options, const BrickFill& fill) {
  Volume volume(dims, 0, options);
  const int e = options.brick_edge;
  parallel_for(
      volume.brick_count(),
      [&](int64_t i) {
        const glm::ivec3 b = volume.brick_coord(i);
        const Box box = volume.brick_box(b);
        thread_local std::vector<uint8_t> region;
        region.resize(static_cast<size_t>(box.voxel_count()));
        fill(box, region);
        std::span<uint8_t> voxels = brick_buffer(e);
        const glm::ivec3 s = box.size();
        for (int z = 0; z < s.z; ++z)
          for (int y = 0; y < s.y; ++y)
            std::memcpy(&voxels[(static_cast<size_t>(z) * e + y) * e],
                        &region[(static_cast<size_t>(z) * s.y + y) * s.x],
                        static_cast<size_t>(s.x));
        volume.pad_outside(b, voxels);
        volume.bricks_[static_cast<size_t>(i)].encode(voxels, e, options.levels);
      },
      options.threads);
  return volume;
}

Volume Volume::from_dense(const DenseGrid<uint8_t>& grid, const VolumeOptions& options) {
  return from_bricks(grid.dims(), options, [&grid](const Box& box, std::span<uint8_t> out) {
    const glm::ivec3 s = box.size();
    for (int z = 0; z < s.z; ++z)
      for (int y = 0; y < s.y; ++y)
        std::memcpy(&out[(static_cast<size_t>(z) * s.y + y) * s.x],
                    &grid.at(box.lo.x, box.lo.y + y, box.lo.z + z), static_cast<size_t>(s.x));
  });
}

uint8_t Volume::voxel(glm::ivec3 p) const {
  if (!Box{glm::ivec3(0), dims_}.contains(p)) return 0;
  const int e = options_.brick_edge;
  const glm::ivec3 b = p / e;
  const glm::ivec3 local = p - b * e;
  return brick(b).voxel(local.x, local.y, local.z);
}

void Volume::decode_brick(glm::ivec3 b, std::span<uint8_t> out, int level) const {
  assert(level >= 0 && level <= options_.levels);
  if (level == 0) {
    const auto i = static_cast<int64_t>(brick_index(b));
    const size_t n = static_cast<size_t>(options_.brick_edge) * options_.brick_edge *
                     static_cast<size_t>(options_.brick_edge);
    for (size_t k = 0; k < recent_brick_.size(); ++k)
      if (recent_brick_[k] == i) {
        std::memcpy(out.data(), recent_voxels_.data() + k * n, n);
        return;
      }
  }
  brick(b).extract_level(level, out);
}

void Volume::remember_stored(size_t i, std::span<const uint8_t> voxels) {
  const size_t n = voxels.size();
  if (recent_voxels_.empty()) recent_voxels_.resize(recent_brick_.size() * n);
  size_t slot = recent_brick_.size();
  for (size_t k = 0; k < recent_brick_.size(); ++k)
    if (recent_brick_[k] == static_cast<int64_t>(i)) slot = k;
  if (slot == recent_brick_.size()) {
    slot = static_cast<size_t>(recent_next_);
    recent_next_ = (recent_next_ + 1) % kRecentBricks;
  }
  recent_brick_[slot] = static_cast<int64_t>(i);
  std::memcpy(recent_voxels_.data() + slot * n, voxels.data(), n);
}

void Volume::forget_stored(size_t i) {
  for (int64_t& slot : recent_brick_)
    if (slot == static_cast<int64_t>(i)) slot = -1;
}

DenseGrid<uint8_t> Volume::read(const Box& region, int level) const {
  DenseGrid<uint8_t> out(region.size(), 0);
  const int m = options_.brick_edge >> level;
  const Box inside = intersect(region, Box{glm::ivec3(0), level_dims(level)});
  if (inside.empty()) return out;
  const Box bricks{inside.lo / m, (inside.hi - 1) / m + 1};
  std::span<uint8_t> cube = brick_buffer(options_.brick_edge).first(static_cast<size_t>(m) * m * m);
  for (int z = bricks.lo.z; z < bricks.hi.z; ++z)
    for (int y = bricks.lo.y; y < bricks.hi.y; ++y)
      for (int x = bricks.lo.x; x < bricks.hi.x; ++x) {
        const glm::ivec3 b{x, y, z};
        decode_brick(b, cube, level);
        copy_cube_into(cube, m, b * m, out, region.lo, inside);
      }
  return out;
}

DenseGrid<uint8_t> Volume::to_dense(int level) const {
  const glm::ivec3 d = level_dims(level);
  DenseGrid<uint8_t> out(d, 0);
  const int m = options_.brick_edge >> level;
  // Bricks write disjoint parts of `out`, so they can be decoded concurrently.
  parallel_for(
      brick_count(),
      [&](int64_t i) {
        const glm::ivec3 b = brick_coord(i);
        std::span<uint8_t> cube =
            brick_buffer(options_.brick_edge).first(static_cast<size_t>(m) * m * m);
        decode_brick(b, cube, level);
        copy_cube_into(cube, m, b * m, out, glm::ivec3(0), Box{glm::ivec3(0), d});
      },
      options_.threads);
  return out;
}

void Volume::replace_brick(glm::ivec3 b, Brick brick) {
  const size_t i = brick_index(b);
  bricks_[i] = std::move(brick);
  ++versions_[i];
  ++stores_;
  // Its decoded copy among the recent bricks is no longer its voxels.
  for (int64_t& recent : recent_brick_)
    if (recent == static_cast<int64_t>(i)) recent = -1;
}

void Volume::store_brick(glm::ivec3 b, std::span<uint8_t> voxels) {
  store_brick(b, voxels, Box{});  // no known changed part: the whole re-encode
}

void Volume::store_brick(glm::ivec3 b, std::span<uint8_t> voxels, const Box& changed) {
  encode_stored(b, voxels, changed);
  const size_t i = brick_index(b);
  remember_stored(i, voxels);
  count_stored(i);
}

void Volume::encode_stored(glm::ivec3 b, std::span<uint8_t> voxels, const Box& changed) {
  const Box box = brick_box(b);
  const Box local = intersect(changed, box);
  const int e = options_.brick_edge;
  Brick& brick = bricks_[brick_index(b)];
  // A far-face brick's padding repeats its last voxels: a change there can
  // reach beyond the box, so it takes the whole re-encode (as does a store
  // with no changed part named).
  if (local.empty() || box.size() != glm::ivec3(e)) {
    pad_outside(b, voxels);
    brick.encode(voxels, e, options_.levels);
    return;
  }
  const glm::ivec3 lo = local.lo - box.lo, hi = local.hi - box.lo;
  brick.encode_region(voxels, e, options_.levels, {lo.x, lo.y, lo.z}, {hi.x, hi.y, hi.z});
}

void Volume::count_stored(size_t i) {
  ++versions_[i];
  ++stores_;
  if (!dirty_flags_[i]) {
    dirty_flags_[i] = 1;
    dirty_list_.push_back(static_cast<int64_t>(i));
  }
}

void Volume::store_bricks(std::span<const BrickStore> stores, int threads) {
  // Below this many bricks a loop's wake-ups cost more than they share.
  constexpr size_t kParallelStores = 8;
  const auto encode = [&](int64_t k) {
    const BrickStore& s = stores[static_cast<size_t>(k)];
    encode_stored(s.brick, s.voxels, s.changed);
  };
  if (stores.size() < kParallelStores) {
    for (size_t k = 0; k < stores.size(); ++k)
      encode(static_cast<int64_t>(k));
  } else {
    parallel_for(static_cast<int64_t>(stores.size()), encode, threads);
  }
  // Only the last kRecentBricks stored stay decoded, as one store after
  // another would leave them; the earlier ones' old voxels are dropped.
  const size_t first_kept = stores.size() > static_cast<size_t>(kRecentBricks)
                                ? stores.size() - static_cast<size_t>(kRecentBricks)
                                : 0;
  for (size_t k = 0; k < stores.size(); ++k) {
    const size_t i = brick_index(stores[k].brick);
    if (k < first_kept) {
      forget_stored(i);
    } else {
      remember_stored(i, stores[k].voxels);
    }
    count_stored(i);
  }
}

void Volume::edit(
    const Box& region,
    const std::function<void(glm::ivec3 brick_origin, std::span<uint8_t> voxels)>& edit) {
  const Box bricks = bricks_overlapping(region);
  // Its own buffer: `edit` may read the volume (smoothing reads neighbours).
  thread_local std::vector<uint8_t> buffer;
  buffer.resize(static_cast<size_t>(options_.brick_edge) * options_.brick_edge *
                options_.brick_edge);
  std::span<uint8_t> voxels = buffer;
  for (int z = bricks.lo.z; z < bricks.hi.z; ++z)
    for (int y = bricks.lo.y; y < bricks.hi.y; ++y)
      for (int x = bricks.lo.x; x < bricks.hi.x; ++x) {
        const glm::ivec3 b{x, y, z};
        decode_brick(b, voxels);
        edit(b * options_.brick_edge, voxels);
        store_brick(b, voxels);
      }
}

void Volume::write(glm::ivec3 origin, const DenseGrid<uint8_t>& values) {
  const Box target{origin, origin + values.dims()};
  const int e = options_.brick_edge;
  edit(target, [&](glm::ivec3 brick_origin, std::span<uint8_t> voxels) {
    const Box overlap =
        intersect(intersect(target, Box{brick_origin, brick_origin + glm::ivec3(e)}),
                  Box{glm::ivec3(0), dims_});
    const int run = overlap.hi.x - overlap.lo.x;
    for (int z = overlap.lo.z; z < overlap.hi.z; ++z)
      for (int y = overlap.lo.y; y < overlap.hi.y; ++y) {
        const glm::ivec3 local = glm::ivec3(overlap.lo.x, y, z) - brick_origin;
        const glm::ivec3 src = glm::ivec3(overlap.lo.x, y, z) - origin;
        std::memcpy(&voxels[(static_cast<size_t>(local.z) * e + local.y) * e + local.x],
                    &values.at(src.x, src.y, src.z), static_cast<size_t>(run));
      }
  });
}

std::vector<glm::ivec3> Volume::take_dirty_bricks() {
  std::sort(dirty_list_.begin(), dirty_list_.end());
  std::vector<glm::ivec3> out;
  out.reserve(dirty_list_.size());
  for (int64_t i : dirty_list_) {
    out.push_back(brick_coord(i));
    dirty_flags_[static_cast<size_t>(i)] = 0;
  }
  dirty_list_.clear();
  return out;
}

VolumeStats Volume::stats() const {
  VolumeStats s;
  s.bricks = brick_count();
  s.memory_bytes = sizeof(*this) + bricks_.capacity() * sizeof(Brick) +
                   versions_.capacity() * sizeof(uint64_t) + dirty_flags_.capacity();
  for (const Brick& b : bricks_) {
    s.memory_bytes += b.memory_bytes() - sizeof(Brick);
    if (b.is_uniform()) {
      ++s.uniform_bricks;
    } else {
      s.detail_coefficients += b.pyramid()->detail_count();
      s.zero_detail_coefficients += b.pyramid()->zero_detail_count();
    }
  }
  return s;
}

namespace {

// FNV-1a over 64-bit little-endian words of the voxel stream (the last word
// zero-padded), with the byte count folded in at the end: eight times fewer
// multiplications than byte-wise FNV, and the words are cut from the whole
// x-fastest stream, so slabs of any size hash alike.
class StreamHash {
 public:
  void add(std::span<const uint8_t> bytes) {
    size_t i = 0;
    while (pending_ > 0 && i < bytes.size())
      push_byte(bytes[i++]);
    for (; i + 8 <= bytes.size(); i += 8) {
      uint64_t w;
      std::memcpy(&w, bytes.data() + i, 8);
      mix(w);
    }
    while (i < bytes.size())
      push_byte(bytes[i++]);
    count_ += bytes.size();
  }
  uint64_t finish() {
    if (pending_ > 0) mix(word_);
    mix(count_);
    return hash_;
  }

 private:
  void push_byte(uint8_t b) {
    word_ |= uint64_t{b} << (8 * pending_);
    if (++pending_ == 8) {
      mix(word_);
      word_ = 0;
      pending_ = 0;
    }
  }
  void mix(uint64_t w) {
    hash_ ^= w;
    hash_ *= 0x100000001b3ull;
    hash_ ^= hash_ >> 29;  // spread the high bits back: FNV alone mixes words poorly
  }
  uint64_t hash_ = 0xcbf29ce484222325ull;
  uint64_t word_ = 0;
  int pending_ = 0;
  uint64_t count_ = 0;
};

}  // namespace

uint64_t Volume::content_hash() const {
  StreamHash hash;
  const int e = options_.brick_edge;
  for (int z0 = 0; z0 < dims_.z; z0 += e) {
    const DenseGrid<uint8_t> slab =
        read(Box{glm::ivec3(0, 0, z0), glm::ivec3(dims_.x, dims_.y, std::min(z0 + e, dims_.z))});
    hash.add(slab.values());
  }
  return hash.finish();
}

}  // namespace sculpt::core
