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
                 std::vector<uint8_t> rims)
      : cache_(cache),
        volume_(volume),
        in_change_(std::move(in_change)),
        moved_(std::move(moved)),
        rims_(std::move(rims)),
        subs_(cache.edge_ / kSub),
        sub_shift_(std::countr_zero(static_cast<unsigned>(cache.edge_ / kSub))),
        edge_shift_(std::countr_zero(static_cast<unsigned>(cache.edge_))) {
    const size_t n = in_change_.size();
    for (int l = 0; l < 2; ++l) {
      decoded_[l] = std::vector<std::vector<uint8_t>>(n);
      once_[l] = std::make_unique<std::once_flag[]>(n);
    }
  }

  // The level of sub-block s (global sub-block coordinates), -1 outside the
  // grid: level 0 outside the change; in it, 0 in a rim, else kCoarse.
  int sub_level(glm::ivec3 s) const {
    const glm::ivec3 b = s >> sub_shift_;
    if (!cache_.in_grid(b)) return -1;
    const size_t i = cache_.index(b);
    if (!in_change_[i]) return 0;
    const unsigned rims = rims_[i];
    const glm::ivec3 l = s & (subs_ - 1);
    for (int a = 0; a < 3; ++a) {
      if ((rims >> (2 * a) & 1u) && l[a] == 0) return 0;
      if ((rims >> (2 * a + 1) & 1u) && l[a] == subs_ - 1) return 0;
    }
    return kCoarse;
  }

  // Finest and coarsest level of the sub-blocks whose closed box holds
  // level-0 point x.
  glm::ivec2 levels_at(glm::ivec3 x) const {
    glm::ivec3 lo, hi;
    for (int a = 0; a < 3; ++a) {
      hi[a] = x[a] >> kCoarse;
      lo[a] = (x[a] & (kSub - 1)) == 0 ? hi[a] - 1 : hi[a];
    }
    glm::ivec2 range(100, -1);
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x0 = lo.x; x0 <= hi.x; ++x0) {
          const int l = sub_level({x0, y, z});
          if (l < 0) continue;
          range = glm::ivec2(std::min(range.x, l), std::max(range.y, l));
        }
    return range;
  }

  // Brick b's level-k voxels (k 0 or kCoarse): the cache's own decode when
  // the brick did not move, else decoded here once.
  const uint8_t* voxels(glm::ivec3 b, int k) const {
    const size_t i = cache_.index(b);
    if (k == 0 && !moved_[i]) {
      const auto kept = cache_.decoded_.find(static_cast<uint64_t>(i) * 8);
      if (kept != cache_.decoded_.end() && kept->second.version == volume_.brick_version(b))
        return kept->second.voxels.data();
    }
    const int l = k == 0 ? 0 : 1;
    std::call_once(once_[l][i], [&] {
      const int m = cache_.edge_ >> k;
      std::vector<uint8_t>& out = decoded_[l][i];
      out.resize(static_cast<size_t>(m) * m * m);
      volume_.decode_brick(b, out, k);
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
    return voxels(p >> shift, k)[(static_cast<size_t>(l.z) * m + l.y) * m + l.x];
  }

  // The sample a box at level k takes at its boundary point p (level-k
  // coordinates): the coarsest sharing level's, as between bricks
  // (MixedLevelMeshCache::shared_value()).
  float agreed(int k, glm::ivec3 p) const {
    const glm::ivec3 x = p << k;
    const glm::ivec2 range = levels_at(x);
    if (range.x == k && range.y == k) return raw(k, p);
    if (range.y <= k) return cache_.tie_moved(raw(range.x, x >> range.x));
    return cache_.tie_moved(detail::interpolate(x, range.y, [&](glm::ivec3 i) {
      const glm::ivec3 xi = i << range.y;
      const int finest = levels_at(xi).x;
      return cache_.tie_moved(raw(finest, xi >> finest));
    }));
  }

  bool in_change(glm::ivec3 b) const { return in_change_[cache_.index(b)] != 0; }
  unsigned rims(glm::ivec3 b) const { return rims_[cache_.index(b)]; }
  int subs() const { return subs_; }

 private:
  const MixedLevelMeshCache& cache_;
  const Volume& volume_;
  const std::vector<uint8_t> in_change_, moved_, rims_;  // per brick
  const int subs_, sub_shift_, edge_shift_;
  // Per brick, its voxels at level 0 ([0]) and kCoarse ([1]) decoded here.
  mutable std::vector<std::vector<uint8_t>> decoded_[2];
  std::unique_ptr<std::once_flag[]> once_[2];
};

void MixedLevelMeshCache::interim_brick(const InterimSampler& sampler, glm::ivec3 b,
                                        BrickMesh& out) const {
  out.clear();
  if (uniform_around(b, 1)) return;
  // The core and the slabs along the sides with a rim, without overlap:
  // x slabs whole, y slabs within the core's x, z slabs within its x and y.
  const unsigned rims = sampler.rims(b);
  const glm::ivec3 lo = b * edge_, hi = (b + 1) * edge_;
  glm::ivec3 core_lo = lo, core_hi = hi;
  for (int a = 0; a < 3; ++a) {
    if (rims >> (2 * a) & 1u) core_lo[a] += kSub;
    if (rims >> (2 * a + 1) & 1u) core_hi[a] -= kSub;
  }
  std::vector<MarchBox> boxes;
  boxes.push_back({kCoarse, core_lo, core_hi});
  for (int a = 0; a < 3; ++a)
    for (int high = 0; high < 2; ++high) {
      if (!(rims >> (2 * a + high) & 1u)) continue;
      MarchBox slab{0, lo, hi};
      for (int before = 0; before < a; ++before) {
        slab.lo[before] = core_lo[before];
        slab.hi[before] = core_hi[before];
      }
      slab.lo[a] = high ? core_hi[a] : lo[a];
      slab.hi[a] = high ? hi[a] : core_lo[a];
      boxes.push_back(slab);
    }

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
          const uint8_t* src = sampler.voxels(nb, k) +
                               (static_cast<size_t>(p0.z - nb.z * m) * m + (p0.y - nb.y * m)) * m;
          for (; x < run_end; ++x)
            row[x - p0.x] = src[x - nb.x * m];
        }
      }
    // The box's faces: where sub-blocks of another level touch one, its
    // samples follow the rule of mixed levels. Faces where all are of the
    // box's level keep their plain voxels, as do the faces' insides.
    unsigned coarser_faces = 0;
    for (int face = 0; face < 6; ++face) {
      const int a = face / 2, u = (a + 1) % 3, v = (a + 2) % 3;
      const int plane = (face & 1) ? box.hi[a] : box.lo[a];
      // The sub-blocks touching the face's closed rectangle, both sides.
      bool mixed = false, coarser = false;
      for (int sa = (plane >> kCoarse) - 1; sa <= (plane >> kCoarse); ++sa)
        for (int su = (box.lo[u] >> kCoarse) - 1; su <= (box.hi[u] >> kCoarse); ++su)
          for (int sv = (box.lo[v] >> kCoarse) - 1; sv <= (box.hi[v] >> kCoarse); ++sv) {
            glm::ivec3 sb;
            sb[a] = sa;
            sb[u] = su;
            sb[v] = sv;
            const int l = sampler.sub_level(sb);
            if (l < 0 || l == k) continue;
            mixed = true;
            // Across the face's inside: what a gap there would face.
            const bool across = sa == ((face & 1) ? (plane >> kCoarse) : (plane >> kCoarse) - 1);
            if (l > k && across) coarser = true;
          }
      if (coarser) coarser_faces |= 1u << face;
      if (!mixed) continue;
      const int p_plane = plane >> k;
      for (int pu = box.lo[u] >> k; pu <= box.hi[u] >> k; ++pu)
        for (int pv = box.lo[v] >> k; pv <= box.hi[v] >> k; ++pv) {
          glm::ivec3 p;
          p[a] = p_plane;
          p[u] = pu;
          p[v] = pv;
          const glm::ivec3 q = p - origin + 1;
          block[(static_cast<size_t>(q.z) * side.y + q.y) * side.x + q.x] = sampler.agreed(k, p);
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
  std::vector<uint8_t> rims(n, 0);
  for (glm::ivec3 b : change) {
    if (level_of(b) != 0) return {};
    unsigned r = 0;
    for (glm::ivec3 d : kAround) {
      const glm::ivec3 nb = b + d;
      if (!in_grid(nb)) continue;
      if (level_of(nb) != 0) return {};
      if (in_change[index(nb)] || bricks_[index(nb)].mesh.empty()) continue;
      // A slab along one side it touches holds every sub-block touching
      // it: a side already in a rim if there is one.
      int side = -1;
      for (int a = 0; a < 3; ++a) {
        if (d[a] == 0) continue;
        const int s = 2 * a + (d[a] > 0 ? 1 : 0);
        if (side < 0 || (r >> s & 1u)) side = s;
        if (r >> s & 1u) break;
      }
      r |= 1u << side;
    }
    rims[index(b)] = static_cast<uint8_t>(r);
  }
  const InterimSampler sampler(*this, volume, std::move(in_change), std::move(moved),
                               std::move(rims));
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
