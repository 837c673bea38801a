#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/grid/grid_index.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cassert>
#include <cmath>
#include <cstring>

#include "sculpt/core/util/parallel_for.h"
#include "sculpt/core/util/progress.h"

namespace sculpt::core {

MeshCache::MeshCache(int level, const MarchingCubesOptions& options)
    : level_(level), options_(options) {
  assert(level >= 0);
}

void MeshCache::reset(const Volume& volume) {
  assert(level_ <= volume.levels());
  volume_ = &volume;
  dims_ = volume.dims();
  level_dims_ = volume.level_dims(level_);
  grid_ = volume.brick_grid();
  m_ = volume.brick_edge() >> level_;
  bricks_.clear();
  bricks_.resize(static_cast<size_t>(volume.brick_count()));
}

namespace {

constexpr uint32_t kAllOffsets = (1u << 27) - 1;

// parallel_for wakes pooled threads rather than starting them, so even the
// few bricks of one dab (each far longer to decode or march than a wake-up)
// are worth sharing.
constexpr int64_t kParallelMinBricks = 2;

int threads_for(int64_t items, int threads) {
  return items < kParallelMinBricks ? 1 : threads;
}

// Largest brick edge (VolumeOptions::brick_edge).
constexpr int kMaxBrickEdge = 128;

// Copies rows_z x rows_y rows of `run` bytes. Bricks copy into a re-mesh's
// block in runs of the brick edge (its own rows) and of one or two voxels
// (its neighbours'): fixed-size copies compile to a few moves, where a
// memcpy call per row cost as much as marching the brick.
template <int kRun>
void copy_rows_fixed(uint8_t* dst, size_t dst_row, size_t dst_plane, const uint8_t* src,
                     size_t src_row, size_t src_plane, int rows_y, int rows_z) {
  for (int z = 0; z < rows_z; ++z)
    for (int y = 0; y < rows_y; ++y)
      std::memcpy(dst + z * dst_plane + y * dst_row, src + z * src_plane + y * src_row, kRun);
}

void copy_rows(uint8_t* dst, size_t dst_row, size_t dst_plane, const uint8_t* src, size_t src_row,
               size_t src_plane, int run, int rows_y, int rows_z) {
  switch (run) {
    case 1:
      return copy_rows_fixed<1>(dst, dst_row, dst_plane, src, src_row, src_plane, rows_y, rows_z);
    case 2:
      return copy_rows_fixed<2>(dst, dst_row, dst_plane, src, src_row, src_plane, rows_y, rows_z);
    case 8:
      return copy_rows_fixed<8>(dst, dst_row, dst_plane, src, src_row, src_plane, rows_y, rows_z);
    case 16:
      return copy_rows_fixed<16>(dst, dst_row, dst_plane, src, src_row, src_plane, rows_y, rows_z);
    case 32:
      return copy_rows_fixed<32>(dst, dst_row, dst_plane, src, src_row, src_plane, rows_y, rows_z);
    default:
      for (int z = 0; z < rows_z; ++z)
        for (int y = 0; y < rows_y; ++y)
          std::memcpy(dst + z * dst_plane + y * dst_row, src + z * src_plane + y * src_row,
                      static_cast<size_t>(run));
  }
}

// Whether two rows of `n` bytes are equal; fixed-size compares of the
// usual brick edges compile inline, where a memcmp call per row of a
// changed brick was a few percent of a re-mesh after a dab.
bool rows_equal(const uint8_t* a, const uint8_t* b, int n) {
  switch (n) {
    case 8:
      return std::memcmp(a, b, 8) == 0;
    case 16:
      return std::memcmp(a, b, 16) == 0;
    case 32:
      return std::memcmp(a, b, 32) == 0;
    default:
      return std::memcmp(a, b, static_cast<size_t>(n)) == 0;
  }
}

}  // namespace

void MeshCache::classify(std::span<const uint8_t> voxels, CachedBrick& cb) const {
  // The sub-box of the 27 offsets (the voxels brick b + d reads from this
  // brick, the same sub-boxes refresh() compares) that a row falls in depends
  // only on whether its y and its z are among the first two (d = -1) and
  // whether they are the last (d = +1). Rows of each such class are ORed and
  // ANDed together byte by byte (inside flags), which vectorises; the
  // classes' first two, all and last bytes then say which sub-boxes hold
  // voxels inside and outside.
  const int m = m_;
  const int threshold = static_cast<int>(std::floor(options_.iso)) + 1;  // v > iso
  const auto t8 = static_cast<uint8_t>(std::clamp(threshold, 0, 255));
  auto row_class = [m](int c) { return (c < 2 ? 1 : 0) | (c == m - 1 ? 2 : 0); };
  // A class no row falls in keeps any = 0, every = 1: it adds no bits.
  alignas(64) uint8_t any[4][4][kMaxBrickEdge], every[4][4][kMaxBrickEdge];
  std::memset(any, 0, sizeof any);
  std::memset(every, 1, sizeof every);
  size_t i = 0;
  for (int z = 0; z < m; ++z)
    for (int y = 0; y < m; ++y, i += static_cast<size_t>(m)) {
      const int zc = row_class(z), yc = row_class(y);
      uint8_t* a = any[zc][yc];
      uint8_t* e = every[zc][yc];
      const uint8_t* row = &voxels[i];
      for (int x = 0; x < m; ++x) {
        const auto in = static_cast<uint8_t>(row[x] >= t8);
        a[x] |= in;
        e[x] &= in;
      }
    }
  const int lo_n = std::min(2, m);
  uint32_t any_in = 0, any_out = 0;
  for (int zc = 0; zc < 4; ++zc)
    for (int yc = 0; yc < 4; ++yc) {
      const uint8_t* a = any[zc][yc];
      const uint8_t* e = every[zc][yc];
      // Per dx + 1: inside somewhere, outside somewhere.
      const bool in[3] = {a[0] || a[lo_n - 1], std::find(a, a + m, 1) != a + m, a[m - 1] != 0};
      const bool out[3] = {!e[0] || !e[lo_n - 1], std::find(e, e + m, 0) != e + m, e[m - 1] == 0};
      for (int dz = -1; dz <= 1; ++dz) {
        if ((dz == -1 && !(zc & 1)) || (dz == 1 && !(zc & 2))) continue;
        for (int dy = -1; dy <= 1; ++dy) {
          if ((dy == -1 && !(yc & 1)) || (dy == 1 && !(yc & 2))) continue;
          for (int dx = 0; dx < 3; ++dx) {
            const uint32_t bit = 1u << ((dz + 1) * 9 + (dy + 1) * 3 + dx);
            if (in[dx]) any_in |= bit;
            if (out[dx]) any_out |= bit;
          }
        }
      }
    }
  cb.any_inside = any_in;
  cb.any_outside = any_out;
}

uint32_t MeshCache::refresh(const Volume& volume, glm::ivec3 b, bool first) {
  CachedBrick& cb = bricks_[index(b)];
  cb.version = volume.brick_version(b);
  const size_t n = static_cast<size_t>(m_) * m_ * m_;
  thread_local std::vector<uint8_t> fresh;
  uint8_t fresh_uniform = 0;
  bool fresh_is_uniform = volume.brick(b).is_uniform();
  if (fresh_is_uniform) {
    fresh_uniform = volume.brick(b).uniform_value();
    fresh.clear();
  } else {
    fresh.resize(n);
    volume.decode_brick(b, fresh, level_);
    // A detailed brick can still be uniform at a coarse level.
    if (std::all_of(fresh.begin(), fresh.end(), [&](uint8_t v) { return v == fresh[0]; })) {
      fresh_is_uniform = true;
      fresh_uniform = fresh[0];
      fresh.clear();
    }
  }
  uint32_t mask = 0;
  if (!first) {
    // Bounding box of the voxels that changed, in brick-local coordinates.
    glm::ivec3 lo(m_), hi(-1);
    const bool old_is_uniform = cb.voxels.empty();
    if (old_is_uniform && fresh_is_uniform) {
      if (cb.uniform != fresh_uniform) lo = glm::ivec3(0), hi = glm::ivec3(m_ - 1);
    } else {
      size_t i = 0;
      for (int z = 0; z < m_; ++z)
        for (int y = 0; y < m_; ++y) {
          const uint8_t* a = old_is_uniform ? nullptr : &cb.voxels[i];
          const uint8_t* f = fresh_is_uniform ? nullptr : &fresh[i];
          if (a && f && rows_equal(a, f, m_)) {
            i += static_cast<size_t>(m_);
            continue;
          }
          // Only the row's first and last changed voxels can widen the box.
          auto differs = [&](int x) {
            return (a ? a[x] : cb.uniform) != (f ? f[x] : fresh_uniform);
          };
          int first_x = 0;
          while (first_x < m_ && !differs(first_x))
            ++first_x;
          if (first_x < m_) {
            int last_x = m_ - 1;
            while (!differs(last_x))
              --last_x;
            lo = glm::min(lo, glm::ivec3(first_x, y, z));
            hi = glm::max(hi, glm::ivec3(last_x, y, z));
          }
          i += static_cast<size_t>(m_);
        }
    }
    if (hi.x >= 0) {
      // Brick b + d reads from b: all of it (d = 0), its first two layers
      // (d = -1: the cells and normals of b - 1 reach two voxels past its far
      // face) or its last layer (d = +1: normals reach one voxel back).
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const glm::ivec3 d(dx, dy, dz);
            bool touches = true;
            for (int a = 0; a < 3; ++a) {
              const int from = d[a] == 1 ? m_ - 1 : 0;
              const int to = d[a] == -1 ? std::min(2, m_) : m_;  // exclusive
              touches = touches && hi[a] >= from && lo[a] < to;
            }
            if (touches) mask |= 1u << ((dz + 1) * 9 + (dy + 1) * 3 + (dx + 1));
          }
    }
  }
  cb.uniform = fresh_uniform;
  if (fresh_is_uniform) {
    const bool in = static_cast<float>(fresh_uniform) > options_.iso;
    cb.any_inside = in ? kAllOffsets : 0;
    cb.any_outside = in ? 0 : kAllOffsets;
  } else {
    classify(fresh, cb);
  }
  if (fresh_is_uniform) {
    cb.voxels.clear();
    cb.voxels.shrink_to_fit();
  } else {
    cb.voxels.swap(fresh);
  }
  return mask;
}

MeshCache::MarchRegion MeshCache::march_region(glm::ivec3 b) const {
  glm::ivec3 c0, c1;
  for (int a = 0; a < 3; ++a) {
    c0[a] = b[a] * m_ - (b[a] == 0 ? 1 : 0);
    c1[a] = std::min((b[a] + 1) * m_, level_dims_[a]);
  }
  MarchRegion r;
  r.cells_lo = c0;
  r.cells_hi = c1;
  r.voxels = Box{c0 - 1, c1 + 2};
  r.inside = intersect(r.voxels, Box{glm::ivec3(0), level_dims_});
  r.bricks = Box{r.inside.lo / m_, (r.inside.hi - 1) / m_ + 1};
  return r;
}

bool MeshCache::has_surface(glm::ivec3 b) const {
  const MarchRegion r = march_region(b);
  const Box& nbs = r.bricks;
  // No surface unless the voxels this brick reads (the sub-boxes of its
  // neighbours, and the empty outside) hold both sides of the iso-level.
  bool any_in = false, any_out = r.inside != r.voxels;
  for (int z = nbs.lo.z; z < nbs.hi.z; ++z)
    for (int y = nbs.lo.y; y < nbs.hi.y; ++y)
      for (int x = nbs.lo.x; x < nbs.hi.x; ++x) {
        const glm::ivec3 d = b - glm::ivec3(x, y, z);  // b is neighbour (x, y, z) + d
        if (glm::any(glm::greaterThan(glm::abs(d), glm::ivec3(1)))) {
          // Bricks of one voxel (the coarsest level): the halo reaches two
          // bricks away, beyond the summaries; assume both sides.
          any_in = any_out = true;
          continue;
        }
        const uint32_t bit = 1u << ((d.z + 1) * 9 + (d.y + 1) * 3 + (d.x + 1));
        const CachedBrick& nb = bricks_[index({x, y, z})];
        any_in = any_in || (nb.any_inside & bit) != 0;
        any_out = any_out || (nb.any_outside & bit) != 0;
      }
  return any_in && any_out;
}

void MeshCache::remesh(glm::ivec3 b, std::vector<uint8_t>& scratch) {
  CachedBrick& cb = bricks_[index(b)];
  const MarchRegion r = march_region(b);
  const Box& region = r.voxels;
  const Box& inside = r.inside;
  const Box& nbs = r.bricks;
  const glm::ivec3 size = region.size();
  scratch.resize(static_cast<size_t>(region.voxel_count()));
  if (inside != region) std::fill(scratch.begin(), scratch.end(), uint8_t{0});
  for (int bz = nbs.lo.z; bz < nbs.hi.z; ++bz)
    for (int by = nbs.lo.y; by < nbs.hi.y; ++by)
      for (int bx = nbs.lo.x; bx < nbs.hi.x; ++bx) {
        const glm::ivec3 nb_coord{bx, by, bz};
        const CachedBrick& nb = bricks_[index(nb_coord)];
        const glm::ivec3 nb_lo = nb_coord * m_;
        const Box part = intersect(inside, Box{nb_lo, nb_lo + m_});
        const int run = part.hi.x - part.lo.x;
        const size_t dst_row = static_cast<size_t>(size.x);
        const size_t dst_plane = dst_row * static_cast<size_t>(size.y);
        uint8_t* dst_first = &scratch[(static_cast<size_t>(part.lo.z - region.lo.z) * size.y +
                                       (part.lo.y - region.lo.y)) *
                                          size.x +
                                      (part.lo.x - region.lo.x)];
        const int rows_y = part.hi.y - part.lo.y, rows_z = part.hi.z - part.lo.z;
        if (nb.voxels.empty()) {
          // A uniform brick: every row copies one row of its value.
          std::array<uint8_t, kMaxBrickEdge> row;
          std::memset(row.data(), nb.uniform, static_cast<size_t>(run));
          copy_rows(dst_first, dst_row, dst_plane, row.data(), 0, 0, run, rows_y, rows_z);
          continue;
        }
        const glm::ivec3 l = part.lo - nb_lo;
        const size_t src_row = static_cast<size_t>(m_), src_plane = src_row * src_row;
        const uint8_t* src_first = &nb.voxels[(static_cast<size_t>(l.z) * m_ + l.y) * m_ + l.x];
        copy_rows(dst_first, dst_row, dst_plane, src_first, src_row, src_plane, run, rows_y,
                  rows_z);
      }
  MarchBlock block;
  block.voxels = scratch.data();
  block.cells = r.cells_hi - r.cells_lo;
  block.origin = r.cells_lo;
  block.level_dims = level_dims_;
  block.level = level_;
  block.iso = options_.iso;
  march_block(block, cb.mesh);
}

MeshUpdate MeshCache::update(const Volume& volume, Progress* progress) {
  const bool first = volume_ != &volume || volume.dims() != dims_ || volume.brick_grid() != grid_ ||
                     (volume.brick_edge() >> level_) != m_;
  if (first) reset(volume);
  const auto count = static_cast<int64_t>(bricks_.size());
  auto coord = [&](int64_t i) { return grid_position(i, grid_); };
  std::vector<int64_t> changed;
  for (int64_t i = 0; i < count; ++i) {
    if (first || volume.brick_version(coord(i)) != bricks_[static_cast<size_t>(i)].version) {
      changed.push_back(i);
    }
  }
  MeshUpdate stats;
  stats.bricks_changed = static_cast<int64_t>(changed.size());
  if (changed.empty()) return stats;

  // Decoding takes about as long per brick as marching it.
  ProgressStage refreshing(progress, 0.0, 0.4, static_cast<int64_t>(changed.size()));
  refreshing.step(0);
  std::vector<uint32_t> masks(changed.size());
  std::atomic<int64_t> decoded{0};
  parallel_for(
      static_cast<int64_t>(changed.size()),
      [&](int64_t k) {
        const glm::ivec3 b = coord(changed[static_cast<size_t>(k)]);
        if (!volume.brick(b).is_uniform()) decoded.fetch_add(1, std::memory_order_relaxed);
        masks[static_cast<size_t>(k)] = refresh(volume, b, first);
      },
      threads_for(static_cast<int64_t>(changed.size()), options_.threads), refreshing);
  stats.bricks_decoded = decoded.load();
  if (cancelled(progress)) {
    volume_ = nullptr;  // half-refreshed bricks: the next update starts over
    return stats;
  }

  std::vector<int64_t> dirty;
  if (first) {
    dirty.resize(static_cast<size_t>(count));
    for (int64_t i = 0; i < count; ++i)
      dirty[static_cast<size_t>(i)] = i;
  } else {
    std::vector<uint8_t> flag(static_cast<size_t>(count), 0);
    for (size_t k = 0; k < changed.size(); ++k) {
      const glm::ivec3 b = coord(changed[k]);
      if (m_ < 2 && masks[k] != 0) {
        // One-voxel bricks: normals read two bricks away on the low side.
        for (int dz = -2; dz <= 1; ++dz)
          for (int dy = -2; dy <= 1; ++dy)
            for (int dx = -2; dx <= 1; ++dx) {
              const glm::ivec3 nb = b + glm::ivec3(dx, dy, dz);
              if (glm::all(glm::greaterThanEqual(nb, glm::ivec3(0))) &&
                  glm::all(glm::lessThan(nb, grid_)))
                flag[index(nb)] = 1;
            }
        continue;
      }
      for (int bit = 0; bit < 27; ++bit) {
        if (!((masks[k] >> bit) & 1)) continue;
        const glm::ivec3 nb = b + glm::ivec3(bit % 3 - 1, (bit / 3) % 3 - 1, bit / 9 - 1);
        if (glm::any(glm::lessThan(nb, glm::ivec3(0))) ||
            glm::any(glm::greaterThanEqual(nb, grid_)))
          continue;
        flag[index(nb)] = 1;
      }
    }
    for (int64_t i = 0; i < count; ++i)
      if (flag[static_cast<size_t>(i)]) dirty.push_back(i);
  }
  // Bricks whose neighbourhood is uniform lose their mesh here; only the
  // rest decide whether threads are worth starting (a dab marches a few
  // bricks among dozens of dirty ones).
  std::vector<int64_t> to_march;
  for (const int64_t i : dirty) {
    if (has_surface(coord(i))) {
      to_march.push_back(i);
    } else {
      bricks_[static_cast<size_t>(i)].mesh.clear();
    }
  }
  ProgressStage marching(progress, 0.4, 1.0, static_cast<int64_t>(to_march.size()));
  parallel_for(
      static_cast<int64_t>(to_march.size()),
      [&](int64_t k) {
        thread_local std::vector<uint8_t> scratch;
        remesh(coord(to_march[static_cast<size_t>(k)]), scratch);
      },
      threads_for(static_cast<int64_t>(to_march.size()), options_.threads), marching);
  stats.bricks_meshed = static_cast<int64_t>(to_march.size());
  if (cancelled(progress))
    volume_ = nullptr;
  else if (progress != nullptr)
    progress->report(1.0);
  return stats;
}

int64_t MeshCache::triangle_count() const {
  int64_t n = 0;
  for (const CachedBrick& cb : bricks_)
    n += static_cast<int64_t>(cb.mesh.mesh.triangles.size());
  return n;
}

Mesh MeshCache::welded_mesh() const {
  std::vector<const BrickMesh*> meshes;
  meshes.reserve(bricks_.size());
  for (const CachedBrick& cb : bricks_)
    if (!cb.mesh.empty()) meshes.push_back(&cb.mesh);
  return weld_brick_meshes(meshes);
}

Mesh marching_cubes(const Volume& volume, int level, const MarchingCubesOptions& options) {
  MeshCache cache(level, options);
  cache.update(volume);
  return cache.welded_mesh();
}

}  // namespace sculpt::core
