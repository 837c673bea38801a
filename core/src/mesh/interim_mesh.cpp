// A big change's first meshes: MixedLevelMeshCache::interim_meshes().
//
// Why: a 66-voxel ball re-meshes 60-140 bricks at full detail, 5-11 ms on
// two cores beside a software renderer, after the 2-5 ms of sculpting it;
// its first mesh then comes 8-16 ms after the report, where the target is
// 4. Marched at level 2, a brick has a sixty-fourth of the cells.
//
// How, without touching the bricks around the change: each changed brick is
// cut into sub-blocks one level-2 voxel (4 voxels) a side. Sub-blocks that
// touch a brick outside the change with a surface (a face, edge or corner
// of it) are fine, at level 0: that brick's mesh was marched from the plain
// voxels on the side they share, and the fine sub-blocks read the same ones
// there, so the two surfaces meet exactly. Every other sub-block of the
// change is coarse, at level 2. Where sub-blocks of two levels meet, inside a
// brick or between two changed bricks, the rule of mixed levels applies as
// between bricks (mixed_level_mesh.h): a point shared by levels takes the
// coarsest sharing level's samples, interpolated on the finer grids, and the
// finer side stitches the thin gaps it leaves. A brick's fine sub-blocks
// are the slabs along its sides (a rim), so a brick marches as at most
// seven boxes: the coarse core and up to six fine slabs.
//
// Bricks outside the change whose mesh is empty keep it: every sample they
// read is on one side of the iso-level, and every sample the change's bricks
// read where they meet them is either one of those or interpolated between
// them, so no crossing lies on the faces they share.

#include <algorithm>
#include <atomic>
#include <array>
#include <bit>
#include <memory>
#include <mutex>
#include <vector>

#include "mesh/level_interpolation.h"
#include "mesh/march_cells.h"
#include "mesh/stitch_gaps.h"
#include "sculpt/core/mesh/mixed_level_mesh.h"
#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

constexpr int kCoarse = MixedLevelMeshCache::kInterimLevel;
constexpr int kSub = 1 << kCoarse;  // a sub-block's edge, level-0 voxels

// The 26 offsets to a brick's neighbours.
constexpr std::array<glm::ivec3, 26> neighbour_offsets() {
  std::array<glm::ivec3, 26> out{};
  int n = 0;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (dx != 0 || dy != 0 || dz != 0) out[static_cast<size_t>(n++)] = {dx, dy, dz};
  return out;
}

// A brick's sub-blocks in 27 regions, by where they lie along each axis
// (the low side's layer, between, the high side's): e in {-1, 0, 1}^3.
constexpr int region_bit(glm::ivec3 e) {
  return ((e.z + 1) * 3 + (e.y + 1)) * 3 + (e.x + 1);
}

// A box a brick's interim mesh is marched in: level-0 voxels [lo, hi], at
// level `level`.
struct MarchBox {
  int level = 0;
  glm::ivec3 lo{0}, hi{0};
  bool empty() const { return glm::any(glm::lessThanEqual(hi, lo)); }
};

}  // namespace

// The levels of the change's sub-blocks, the voxels they read, and the rule
// their samples follow; read-only while bricks are meshed in parallel
// (decodes are made once, on first use, under a per-brick flag).
class MixedLevelMeshCache::InterimSampler {
 public:
  InterimSampler(const MixedLevelMeshCache& cache, const Volume& volume,
                 std::vector<uint8_t> in_change, std::vector<uint8_t> moved,
                 std::vector<uint32_t> fine_regions)
      : cache_(cache),
        volume_(volume),
        in_change_(std::move(in_change)),
        moved_(std::move(moved)),
        fine_regions_(std::move(fine_regions)),
        subs_(cache.edge_ / kSub),
        sub_shift_(std::countr_zero(static_cast<unsigned>(cache.edge_ / kSub))),
        edge_shift_(std::countr_zero(static_cast<unsigned>(cache.edge_))) {
    const size_t n = in_change_.size();
    for (int l = 0; l < 2; ++l) {
      decoded_[l] = std::vector<std::vector<uint8_t>>(n);
      once_[l] = std::make_unique<std::once_flag[]>(n);
      ready_[l] = std::make_unique<std::atomic<uint8_t>[]>(n);
    }
    // The cache's level-0 voxels of the bricks around the change that did
    // not move, looked up once (a map lookup a sample was most of the time).
    kept_.assign(n, nullptr);
    for (size_t i = 0; i < n; ++i) {
      if (!in_change_[i]) continue;
      const glm::ivec3 b = grid_position(static_cast<int64_t>(i), cache.grid_);
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const glm::ivec3 nb = b + glm::ivec3(dx, dy, dz);
            if (!cache.in_grid(nb)) continue;
            const size_t j = cache.index(nb);
            if (moved_[j] || kept_[j] != nullptr) continue;
            const auto it = cache.decoded_.find(static_cast<uint64_t>(j) * 8);
            if (it != cache.decoded_.end() && it->second.version == volume.brick_version(nb))
              kept_[j] = it->second.voxels.data();
          }
    }
  }

  // The level of sub-block s (global sub-block coordinates), -1 outside the
  // grid: level 0 outside the change; in it, 0 in a rim, else kCoarse.
  int sub_level(glm::ivec3 s) const {
    const glm::ivec3 b = s >> sub_shift_;
    if (!cache_.in_grid(b)) return -1;
    const size_t i = cache_.index(b);
    if (!in_change_[i]) return 0;
    const glm::ivec3 l = s & (subs_ - 1);
    const glm::ivec3 e(region_side(l.x), region_side(l.y), region_side(l.z));
    if (fine_regions_[i] >> region_bit(e) & 1u) return 0;
    return kCoarse;
  }

  // Brick b's level-k voxels (k 0 or kCoarse): the cache's own decode when
  // the brick did not move, else decoded here once.
  // A uniform brick has none: null (its value is uniform_value()).
  const uint8_t* voxels(glm::ivec3 b, int k) const {
    const size_t i = cache_.index(b);
    if (k == 0 && kept_[i] != nullptr) return kept_[i];
    if (volume_.brick(b).is_uniform()) return nullptr;
    const int l = k == 0 ? 0 : 1;
    std::call_once(once_[l][i], [&] {
      const int m = cache_.edge_ >> k;
      std::vector<uint8_t>& out = decoded_[l][i];
      out.resize(static_cast<size_t>(m) * m * m);
      volume_.decode_brick(b, out, k);
      ready_[l][i].store(1, std::memory_order_release);
    });
    return decoded_[l][i].data();
  }

  // Level-k voxel p (level coordinates), 0 outside the volume.
  float raw(int k, glm::ivec3 p) const {
    const glm::ivec3 d = cache_.level_dims_[static_cast<size_t>(k)];
    if (glm::any(glm::lessThan(p, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(p, d)))
      return 0.0f;
    const int shift = edge_shift_ - k;
    const int m = 1 << shift;
    const glm::ivec3 l = p & (m - 1);
    const glm::ivec3 b = p >> shift;
    const size_t i = cache_.index(b);
    const size_t at = (static_cast<size_t>(l.z) * m + l.y) * m + l.x;
    if (k == 0 && kept_[i] != nullptr) return kept_[i][at];
    if (ready_[k == 0 ? 0 : 1][i].load(std::memory_order_acquire)) return decoded_[k == 0 ? 0 : 1][i][at];
    // Not decoded (yet): a few voxels of a brick (the coarse points on a
    // face) cost less read one by one from its pyramid than decoded whole.
    if (k == 0) return volume_.brick(b).voxel(l.x, l.y, l.z);
    const uint8_t* v = voxels(b, k);
    return v != nullptr ? v[at] : volume_.brick(b).uniform_value();
  }
  uint8_t uniform_value(glm::ivec3 b) const { return volume_.brick(b).uniform_value(); }

  float tie_moved(float v) const { return cache_.tie_moved(v); }
  bool in_change(glm::ivec3 b) const { return in_change_[cache_.index(b)] != 0; }
  uint32_t fine_regions(glm::ivec3 b) const { return fine_regions_[cache_.index(b)]; }
  // Which third of a brick, along one axis, sub-block l lies in: -1 the
  // low side's layer, 1 the high side's, 0 between.
  int region_side(int l) const { return l == 0 ? -1 : (l == subs_ - 1 ? 1 : 0); }
  int subs() const { return subs_; }

 private:
  const MixedLevelMeshCache& cache_;
  const Volume& volume_;
  const std::vector<uint8_t> in_change_, moved_;  // per brick
  const std::vector<uint32_t> fine_regions_;       // per brick, region_bit()s
  const int subs_, sub_shift_, edge_shift_;
  // Per brick, its voxels at level 0 ([0]) and kCoarse ([1]) decoded here.
  mutable std::vector<std::vector<uint8_t>> decoded_[2];
  std::unique_ptr<std::once_flag[]> once_[2];
  std::unique_ptr<std::atomic<uint8_t>[]> ready_[2];  // decoded_ filled
  std::vector<const uint8_t*> kept_;  // per brick, the cache's level-0 voxels
};

// The levels of the sub-blocks of a brick and of the ring of sub-blocks
// around it (InterimSampler::sub_level()), looked up once a brick: a
// face's levels are read many times.
class SubLevels {
 public:
  template <class Sampler>
  SubLevels(const Sampler& sampler, glm::ivec3 brick) : n_(sampler.subs() + 2) {
    origin_ = brick * sampler.subs() - 1;
    levels_.resize(static_cast<size_t>(n_) * n_ * n_);
    for (int z = 0; z < n_; ++z)
      for (int y = 0; y < n_; ++y)
        for (int x = 0; x < n_; ++x)
          levels_[(static_cast<size_t>(z) * n_ + y) * n_ + x] =
              static_cast<int8_t>(sampler.sub_level(origin_ + glm::ivec3(x, y, z)));
  }
  // Sub-block s (global sub-block coordinates, within the ring).
  int at(glm::ivec3 s) const {
    const glm::ivec3 l = s - origin_;
    return levels_[(static_cast<size_t>(l.z) * n_ + l.y) * n_ + l.x];
  }

 private:
  int n_;
  glm::ivec3 origin_{0};
  std::vector<int8_t> levels_;
};

// The levels of the sub-blocks touching one face of a box (both sides,
// one beyond its edges), and the agreed samples at the level-2 points of
// its closed rectangle, each computed once.
class MixedLevelMeshCache::FaceLevels {
 public:
  FaceLevels(const InterimSampler& sampler, const SubLevels& sub_levels, const MarchBox& box,
             int face)
      : sampler_(sampler), a_(face / 2), u_((a_ + 1) % 3), v_((a_ + 2) % 3) {
    plane_ = (face & 1) ? box.hi[a_] : box.lo[a_];
    lo_ = box.lo;
    size_u_ = box.hi[u_] - box.lo[u_];
    size_v_ = box.hi[v_] - box.lo[v_];
    nu_ = size_u_ / kSub + 2;
    nv_ = size_v_ / kSub + 2;
    levels_.resize(static_cast<size_t>(2 * nu_ * nv_));
    const int across_layer = (face & 1) ? 1 : 0;
    for (int layer = 0; layer < 2; ++layer)
      for (int su = 0; su < nu_; ++su)
        for (int sv = 0; sv < nv_; ++sv) {
          glm::ivec3 sb;
          sb[a_] = (plane_ >> kCoarse) - 1 + layer;
          sb[u_] = (lo_[u_] >> kCoarse) - 1 + su;
          sb[v_] = (lo_[v_] >> kCoarse) - 1 + sv;
          const int l = sub_levels.at(sb);
          level_at(layer, su, sv) = static_cast<int8_t>(l);
          if (l < 0) continue;
          levels_used_ |= 1u << l;
          const bool inside_u = su >= 1 && su < nu_ - 1, inside_v = sv >= 1 && sv < nv_ - 1;
          if (layer == across_layer && inside_u && inside_v && l > 0) coarser_across_ = true;
        }
    column_min_.assign(static_cast<size_t>(nu_ * nv_), 100);
    column_max_.assign(static_cast<size_t>(nu_ * nv_), -1);
    for (int layer = 0; layer < 2; ++layer)
      for (int su = 0; su < nu_; ++su)
        for (int sv = 0; sv < nv_; ++sv) {
          const int l = level_at(layer, su, sv);
          if (l < 0) continue;
          const size_t c = static_cast<size_t>(su * nv_ + sv);
          column_min_[c] = static_cast<int8_t>(std::min<int>(column_min_[c], l));
          column_max_[c] = static_cast<int8_t>(std::max<int>(column_max_[c], l));
        }
  }
  // Whether sub-blocks of another level than k touch the face.
  bool mixed(int k) const { return (levels_used_ & ~(1u << k)) != 0; }
  // Whether the face's inside has coarse sub-blocks across it.
  bool coarser_across() const { return coarser_across_; }
  int plane() const { return plane_; }
  int size_u() const { return size_u_; }
  int size_v() const { return size_v_; }

  // Finest and coarsest level sharing the face's point (cu, cv), level-0
  // voxels from the rectangle's low corner: the sub-blocks of the one, two
  // or four columns (both layers) around it.
  glm::ivec2 levels_at(int cu, int cv) const {
    const int su1 = cu / kSub + 1, sv1 = cv / kSub + 1;
    const int su0 = cu % kSub == 0 ? su1 - 1 : su1, sv0 = cv % kSub == 0 ? sv1 - 1 : sv1;
    glm::ivec2 range(100, -1);
    for (int su = su0; su <= su1; ++su)
      for (int sv = sv0; sv <= sv1; ++sv) {
        const size_t c = static_cast<size_t>(su * nv_ + sv);
        range = glm::ivec2(std::min<int>(range.x, column_min_[c]),
                           std::max<int>(range.y, column_max_[c]));
      }
    return range;
  }
  // The agreed sample at the rectangle's level-2 point (iu, iv): the finest
  // sharing level's voxel, a tie moved below the iso-level.
  float lattice(int iu, int iv) const {
    return lattice_[static_cast<size_t>(iu) * (nv_ - 1) + iv];
  }
  // Computes the lattice's samples (once the face is known to be mixed).
  void read_lattice() {
    lattice_.resize(static_cast<size_t>(nu_ - 1) * (nv_ - 1));
    for (int iu = 0; iu < nu_ - 1; ++iu)
      for (int iv = 0; iv < nv_ - 1; ++iv) {
        glm::ivec3 x;
        x[a_] = plane_;
        x[u_] = lo_[u_] + iu * kSub;
        x[v_] = lo_[v_] + iv * kSub;
        const int finest = levels_at(iu * kSub, iv * kSub).x;
        lattice_[static_cast<size_t>(iu) * (nv_ - 1) + iv] =
            sampler_.tie_moved(sampler_.raw(finest, x >> finest));
      }
  }

 private:
  static constexpr float kUnknown = -1.0f;
  int8_t& level_at(int layer, int su, int sv) {
    return levels_[static_cast<size_t>((layer * nu_ + su) * nv_ + sv)];
  }
  int level_at(int layer, int su, int sv) const {
    return levels_[static_cast<size_t>((layer * nu_ + su) * nv_ + sv)];
  }
  const InterimSampler& sampler_;
  const int a_, u_, v_;
  int plane_ = 0, size_u_ = 0, size_v_ = 0, nu_ = 0, nv_ = 0;
  glm::ivec3 lo_{0};
  std::vector<int8_t> levels_;
  std::vector<int8_t> column_min_, column_max_;  // per column (su, sv), both layers
  unsigned levels_used_ = 0;
  bool coarser_across_ = false;
  std::vector<float> lattice_;
};

void MixedLevelMeshCache::interim_brick(const InterimSampler& sampler, glm::ivec3 b,
                                        BrickMesh& out) const {
  out.clear();
  if (uniform_around(b, 1)) return;
  // The brick's 27 regions (per axis: the low side's layer of sub-blocks,
  // those between, the high side's), each fine or coarse, marched as boxes:
  // runs of one kind along x, rows of the same runs together, then layers
  // of the same rows (a rim along one face is two boxes, not eighteen). A
  // brick with no fine region is one coarse box.
  const uint32_t fine = sampler.fine_regions(b);
  const glm::ivec3 lo = b * edge_;
  const int cut[4] = {0, kSub, edge_ - kSub, edge_};
  auto is_fine = [&](int ex, int ey, int ez) { return (fine >> region_bit({ex, ey, ez}) & 1u) != 0; };
  // A row's runs as a bit pattern: bit x + 1 set where a run starts, bit
  // 4 + x + 1 where it is fine.
  auto row_runs = [&](int ey, int ez) {
    unsigned pattern = 0;
    for (int ex = -1; ex <= 1; ++ex) {
      if (ex == -1 || is_fine(ex, ey, ez) != is_fine(ex - 1, ey, ez)) pattern |= 1u << (ex + 1);
      if (is_fine(ex, ey, ez)) pattern |= 1u << (4 + ex + 1);
    }
    return pattern;
  };
  auto layer_rows = [&](int ez) {
    unsigned rows = 0;
    for (int ey = -1; ey <= 1; ++ey)
      rows |= row_runs(ey, ez) << (8 * (ey + 1));
    return rows;
  };
  std::vector<MarchBox> boxes;
  for (int ez = -1; ez <= 1;) {
    int ez_end = ez + 1;
    while (ez_end <= 1 && layer_rows(ez_end) == layer_rows(ez))
      ++ez_end;
    for (int ey = -1; ey <= 1;) {
      int ey_end = ey + 1;
      while (ey_end <= 1 && row_runs(ey_end, ez) == row_runs(ey, ez))
        ++ey_end;
      for (int ex = -1; ex <= 1;) {
        int ex_end = ex + 1;
        while (ex_end <= 1 && is_fine(ex_end, ey, ez) == is_fine(ex, ey, ez))
          ++ex_end;
        boxes.push_back({is_fine(ex, ey, ez) ? 0 : kCoarse,
                         lo + glm::ivec3(cut[ex + 1], cut[ey + 1], cut[ez + 1]),
                         lo + glm::ivec3(cut[ex_end + 1], cut[ey_end + 1], cut[ez_end + 1])});
        ex = ex_end;
      }
      ey = ey_end;
    }
    ez = ez_end;
  }

  const SubLevels sub_levels(sampler, b);
  thread_local std::vector<float> block;
  BrickMesh part;
  MixedLevelStats stats;
  for (const MarchBox& box : boxes) {
    if (box.empty()) continue;
    const int k = box.level, m = edge_ >> k;
    const glm::ivec3 origin = box.lo >> k, cells = (box.hi - box.lo) >> k, side = cells + 3;
    const glm::ivec3 ld = level_dims_[static_cast<size_t>(k)];
    block.assign(static_cast<size_t>(side.x) * side.y * side.z, 0.0f);
    // Plain level-k voxels, a brick's run of a row at a time.
    for (int z = -1; z <= cells.z + 1; ++z)
      for (int y = -1; y <= cells.y + 1; ++y) {
        const glm::ivec3 p0 = origin + glm::ivec3(-1, y, z);
        if (p0.y < 0 || p0.z < 0 || p0.y >= ld.y || p0.z >= ld.z) continue;
        float* row = &block[(static_cast<size_t>(z + 1) * side.y + (y + 1)) * side.x];
        for (int x = std::max(0, p0.x); x < std::min(ld.x, p0.x + side.x);) {
          const glm::ivec3 nb(x / m, p0.y / m, p0.z / m);
          const int run_end = std::min({ld.x, p0.x + side.x, (nb.x + 1) * m});
          const uint8_t* voxels = sampler.voxels(nb, k);
          if (voxels == nullptr) {
            std::fill(row + (x - p0.x), row + (run_end - p0.x),
                      static_cast<float>(sampler.uniform_value(nb)));
            x = run_end;
            continue;
          }
          const uint8_t* src =
              voxels + (static_cast<size_t>(p0.z - nb.z * m) * m + (p0.y - nb.y * m)) * m;
          for (; x < run_end; ++x)
            row[x - p0.x] = src[x - nb.x * m];
        }
      }
    // The box's faces: where sub-blocks of another level touch one, its
    // samples follow the rule of mixed levels. Faces where all are of the
    // box's level keep their plain voxels.
    unsigned coarser_faces = 0;
    for (int face = 0; face < 6; ++face) {
      FaceLevels f(sampler, sub_levels, box, face);
      if (f.coarser_across()) coarser_faces |= 1u << face;
      if (!f.mixed(k)) continue;
      f.read_lattice();
      const int a = face / 2, u = (a + 1) % 3, v = (a + 2) % 3;
      const int step = 1 << k;
      for (int cu = 0; cu <= f.size_u(); cu += step)
        for (int cv = 0; cv <= f.size_v(); cv += step) {
          const glm::ivec2 range = f.levels_at(cu, cv);
          if (range.x == k && range.y == k) continue;  // the plain voxel
          glm::ivec3 x;
          x[a] = f.plane();
          x[u] = box.lo[u] + cu;
          x[v] = box.lo[v] + cv;
          // A coarse point takes the finest sharing level's voxel; a fine
          // one between coarse points their interpolant (shared_value()).
          const float value = range.y <= k ? f.lattice(cu >> kCoarse, cv >> kCoarse)
                                           : tie_moved(detail::interpolate(
                                                 x, kCoarse, [&](glm::ivec3 i) {
                                                   return f.lattice(i[u] - (box.lo[u] >> kCoarse),
                                                                    i[v] - (box.lo[v] >> kCoarse));
                                                 }));
          const glm::ivec3 q = (x >> k) - origin + 1;
          block[(static_cast<size_t>(q.z) * side.y + q.y) * side.x + q.x] = value;
        }
    }
    detail::march_float_cells(
        block.data(), cells, origin, k, options_.iso,
        [](glm::ivec3, int) { return BrickMesh::kNotSeam; }, part);
    if (part.empty()) continue;
    // A fine slab closes its gaps against coarse sub-blocks across it.
    if (k == 0 && coarser_faces != 0)
      detail::stitch_gaps(glm::vec3(box.lo), glm::vec3(box.hi), coarser_faces,
                          [&](int face, glm::dvec3 mid) {
                            const int a = face / 2;
                            glm::dvec3 across = mid;
                            across[a] += (face & 1) ? 0.5 : -0.5;
                            const glm::ivec3 sb(glm::floor(across / static_cast<double>(kSub)));
                            const int l = sampler.sub_level(sb);
                            return l > 0 ? l : -1;
                          },
                          part.mesh, stats);
    // Appended: the boxes' meshes are drawn together, not welded.
    Mesh& mesh = out.mesh;
    const auto base = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), part.mesh.positions.begin(),
                          part.mesh.positions.end());
    mesh.normals.insert(mesh.normals.end(), part.mesh.normals.begin(), part.mesh.normals.end());
    for (const glm::uvec3& t : part.mesh.triangles)
      mesh.triangles.push_back(t + base);
  }
}

std::vector<MixedLevelMeshCache::InterimMesh> MixedLevelMeshCache::interim_meshes(
    const Volume& volume, std::span<const int> brick_levels, size_t min_bricks) const {
  if (volume_ != &volume || volume.dims() != dims_ || volume.brick_grid() != grid_ ||
      volume.brick_edge() != edge_ || volume.levels() < kCoarse || edge_ / kSub < 2)
    return {};
  if (!std::equal(levels_.begin(), levels_.end(), brick_levels.begin(), brick_levels.end()))
    return {};
  const size_t n = bricks_.size();
  std::vector<uint8_t> moved(n, 0), in_change(n, 0);
  std::vector<glm::ivec3> change;
  for (size_t i = 0; i < n; ++i) {
    const glm::ivec3 b = grid_position(static_cast<int64_t>(i), grid_);
    if (seen_versions_[i] == volume.brick_version(b)) continue;
    moved[i] = 1;
    // Its voxels are in its own box and on the high faces of the bricks
    // below it.
    for (int dz = -1; dz <= 0; ++dz)
      for (int dy = -1; dy <= 0; ++dy)
        for (int dx = -1; dx <= 0; ++dx) {
          const glm::ivec3 nb = b + glm::ivec3(dx, dy, dz);
          if (!in_grid(nb) || in_change[index(nb)]) continue;
          in_change[index(nb)] = 1;
          change.push_back(nb);
        }
  }
  if (change.empty() || change.size() < min_bricks) return {};
  constexpr std::array<glm::ivec3, 26> kAround = neighbour_offsets();
  // An unchanged brick around the change keeps its mesh, marched from the
  // plain voxels of its box. Where its surface reaches a face or edge of
  // its box (a vertex lies on it), every point there must keep its plain
  // voxel in the changed bricks too, or the crossings on the edges beside
  // it would move: the changed bricks' sub-blocks touching that face or
  // edge are fine. Elsewhere the points it shares with changed bricks keep
  // their samples' side of the iso-level (coarse points take the finest
  // voxel, the points between interpolate them), so neither side has a
  // crossing there. Which parts of its boundary a mesh reaches: bit
  // region_bit(direction) for each of the 26 its vertices lie on.
  auto boundary_reached = [&](glm::ivec3 u) {
    const glm::vec3 lo(u * edge_), hi((u + 1) * edge_);
    uint32_t bits = 0;
    for (const glm::vec3& p : bricks_[index(u)].mesh.mesh.positions) {
      glm::ivec3 on(0);
      for (int a = 0; a < 3; ++a)
        on[a] = p[a] == lo[a] ? -1 : (p[a] == hi[a] ? 1 : 0);
      if (on == glm::ivec3(0)) continue;
      for (int m = 1; m < 8; ++m) {  // every region whose closed part holds it
        glm::ivec3 e(0);
        bool valid = true;
        for (int a = 0; a < 3; ++a)
          if (m >> a & 1) {
            valid = valid && on[a] != 0;
            e[a] = on[a];
          }
        if (valid) bits |= 1u << region_bit(e);
      }
    }
    return bits;
  };
  std::vector<uint32_t> fine(n, 0);
  std::vector<uint8_t> kept_around(n, 0);
  for (glm::ivec3 b : change) {
    if (level_of(b) != 0) return {};
    for (glm::ivec3 d : kAround) {
      const glm::ivec3 u = b + d;
      if (!in_grid(u)) continue;
      if (level_of(u) != 0) return {};
      if (in_change[index(u)] || kept_around[index(u)] || bricks_[index(u)].mesh.empty()) continue;
      kept_around[index(u)] = 1;
      const uint32_t reached = boundary_reached(u);
      for (glm::ivec3 r : kAround) {
        // A corner is one point, which keeps its plain voxel anyway.
        if (!(reached >> region_bit(r) & 1u) || glm::all(glm::notEqual(r, glm::ivec3(0))))
          continue;
        for (glm::ivec3 d2 : kAround) {
          const glm::ivec3 c = u + d2;
          if (!in_grid(c) || !in_change[index(c)]) continue;
          // Along each axis, the layers of c that touch the face or edge
          // (bit e + 1 for layer e).
          unsigned sides[3];
          for (int a = 0; a < 3; ++a) {
            if (r[a] == 0)
              sides[a] = d2[a] == 0 ? 7u : (d2[a] < 0 ? 4u : 1u);
            else
              sides[a] = d2[a] == 0 ? (r[a] < 0 ? 1u : 4u) : (d2[a] == r[a] ? (r[a] < 0 ? 4u : 1u) : 0u);
          }
          for (int ez = -1; ez <= 1; ++ez)
            for (int ey = -1; ey <= 1; ++ey)
              for (int ex = -1; ex <= 1; ++ex)
                if ((sides[0] >> (ex + 1) & 1u) && (sides[1] >> (ey + 1) & 1u) &&
                    (sides[2] >> (ez + 1) & 1u))
                  fine[index(c)] |= 1u << region_bit({ex, ey, ez});
        }
      }
    }
  }
  const InterimSampler sampler(*this, volume, std::move(in_change), std::move(moved),
                               std::move(fine));
  std::vector<InterimMesh> out(change.size());
  parallel_for(
      static_cast<int64_t>(change.size()),
      [&](int64_t i) {
        InterimMesh& m = out[static_cast<size_t>(i)];
        m.brick = change[static_cast<size_t>(i)];
        interim_brick(sampler, m.brick, m.mesh);
      },
      options_.threads);
  return out;
}

}  // namespace sculpt::core
