#include "sculpt/core/distance/narrow_band.h"
#include "sculpt/core/grid/grid_index.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "chunked_groups.h"
#include "sculpt/core/mesh/point_triangle.h"
#include "sculpt/core/util/parallel_for.h"

// The band kernel is compiled twice, for AVX2 (8 voxels at once) and for
// the baseline (4), and picks the one the CPU runs: one portable binary.
#if defined(__x86_64__) && defined(__GNUC__)
#define SCULPT_DISTANCE_AVX2 1
#else
#define SCULPT_DISTANCE_AVX2 0
#endif
// The AVX2 kernel's helpers pass 8-lane vectors by value; they are internal
// and inlined, so GCC's note that AVX changes the calling convention of such
// functions (reported at the end of the file) does not concern them.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace sculpt::core {

using detail::for_chunks;
using detail::kChunks;

namespace {
constexpr float kInf = std::numeric_limits<float>::infinity();
}  // namespace

namespace {

// What the band kernel needs of one triangle, computed once rather than
// once per brick it reaches.
struct BandTriangle {
  glm::vec3 a, ab, ac, bc;
  // Unit, for the lower bound and the sign; zero for a sliver, whose normal
  // is mostly rounding (then the bound is 0 and the sign comes from
  // MeshDistance).
  glm::vec3 normal;
  // The dual basis of (ab, ac) in the triangle's plane: p - a =
  // u ab + v ac + h normal with u = dot(p - a, dual_ab), v = dot(p - a,
  // dual_ac). p projects into the face when u, v >= 0 and u + v <= 1.
  glm::vec3 dual_ab, dual_ac;
  float uv_limit;  // 1, or -1 when degenerate: no face to project into
  // Heights of b over line ac, c over ab and a over bc (0 for a sliver):
  // -u height_b is how far a point's projection lies beyond line ac.
  float height_b, height_c, height_a;
  float inv_ab2, inv_ac2, inv_bc2;  // 1 / squared edge length, 0 for a zero-length edge
  glm::vec3 centre;
  float radius;       // of the ball about centre that holds the triangle
  glm::ivec3 lo, hi;  // voxels its band can reach, clipped to the grid
};

float inverse_or_zero(float v) {
  return v > 0.0f ? 1.0f / v : 0.0f;
}

BandTriangle band_triangle(const Mesh& mesh, uint32_t t, float band, glm::ivec3 dims) {
  const glm::uvec3 f = mesh.triangles[t];
  const glm::vec3 a = mesh.positions[f.x], b = mesh.positions[f.y], c = mesh.positions[f.z];
  BandTriangle bt;
  bt.a = a;
  bt.ab = b - a;
  bt.ac = c - a;
  bt.bc = c - b;
  const glm::vec3 n = glm::cross(bt.ab, bt.ac);
  const float n2 = glm::dot(n, n);
  bt.dual_ab = n2 > 0.0f ? glm::cross(bt.ac, n) / n2 : glm::vec3(0.0f);
  bt.dual_ac = n2 > 0.0f ? glm::cross(n, bt.ab) / n2 : glm::vec3(0.0f);
  bt.uv_limit = n2 > 0.0f ? 1.0f : -1.0f;
  bt.inv_ab2 = inverse_or_zero(glm::dot(bt.ab, bt.ab));
  bt.inv_ac2 = inverse_or_zero(glm::dot(bt.ac, bt.ac));
  bt.inv_bc2 = inverse_or_zero(glm::dot(bt.bc, bt.bc));
  // The cross product carries a rounding error of about 1e-7 |ab| |ac|: when
  // the angle at a is under ~0.6 degrees (sine < 1e-2) its direction may be
  // off by more than 1e-5 radians, enough to lift the lower bound above
  // the true distance by 1e-4 voxel a few voxels away.
  const bool sliver = !(n2 > 1e-4f * glm::dot(bt.ab, bt.ab) * glm::dot(bt.ac, bt.ac));
  bt.normal = sliver ? glm::vec3(0.0f) : n / std::sqrt(n2);
  const float area2 = sliver ? 0.0f : std::sqrt(n2);  // twice the area
  bt.height_b = area2 * std::sqrt(bt.inv_ac2);
  bt.height_c = area2 * std::sqrt(bt.inv_ab2);
  bt.height_a = area2 * std::sqrt(bt.inv_bc2);
  bt.centre = (a + b + c) / 3.0f;
  bt.radius = std::sqrt(
      std::max({glm::dot(a - bt.centre, a - bt.centre), glm::dot(b - bt.centre, b - bt.centre),
                glm::dot(c - bt.centre, c - bt.centre)}));
  bt.lo = glm::max(glm::ivec3(glm::ceil(glm::min(a, glm::min(b, c)) - band)), glm::ivec3(0));
  bt.hi = glm::min(glm::ivec3(glm::floor(glm::max(a, glm::max(b, c)) + band)), dims - 1);
  return bt;
}

// The grid voxel of value k of the brick at `brick` (brick coordinates).
glm::ivec3 voxel_in_brick(glm::ivec3 brick, int k) {
  constexpr int B = NarrowBand::kBrick;
  return brick * B + glm::ivec3(k % B, (k / B) % B, k / (B * B));
}

// Calls visit(brick index) for every brick that triangle `bt`'s band can
// reach: its clipped box, less the bricks farther than band from its ball.
template <class Visit>
void for_each_brick(const BandTriangle& bt, float band, glm::ivec3 bricks, Visit&& visit) {
  constexpr int B = NarrowBand::kBrick;
  if (bt.lo.x > bt.hi.x || bt.lo.y > bt.hi.y || bt.lo.z > bt.hi.z) return;
  const glm::ivec3 b0 = bt.lo / B, b1 = bt.hi / B;
  const float ball = band + bt.radius;
  for (int bz = b0.z; bz <= b1.z; ++bz)
    for (int by = b0.y; by <= b1.y; ++by)
      for (int bx = b0.x; bx <= b1.x; ++bx) {
        const glm::vec3 lo = glm::vec3(bx, by, bz) * float(B);
        if (point_box_distance_squared(bt.centre, lo, lo + float(B - 1)) >= ball * ball) continue;
        visit(static_cast<int64_t>(grid_index({bx, by, bz}, bricks)));
      }
}

// W voxels of a brick row at once: GCC vector extensions, 8 lanes (one AVX2
// register) or 4 (one SSE2 or NEON register; GCC splits 8-lane vectors
// badly without AVX2, far slower than 4 lanes).
template <int W>
struct Lanes {
  typedef float F __attribute__((vector_size(4 * W)));
  typedef int32_t M __attribute__((vector_size(4 * W)));
  typedef int64_t Pairs __attribute__((vector_size(4 * W)));
};

template <class V>
[[gnu::always_inline]] inline V vmin(V a, V b) {
  return a < b ? a : b;
}

template <class V>
[[gnu::always_inline]] inline V vmax(V a, V b) {
  return a > b ? a : b;
}

template <int W>
[[gnu::always_inline]] inline bool any(typename Lanes<W>::M m) {
  const auto pairs = reinterpret_cast<typename Lanes<W>::Pairs>(m);
  int64_t bits = 0;
  for (int i = 0; i < W / 2; ++i)
    bits |= pairs[i];
  return bits != 0;
}

// Squared distance from the points a + (dx, dy, dz) to the segment from a
// along e (inv_e2 = 1 / |e|^2, 0 when the segment is a point).
template <class V>
[[gnu::always_inline]] inline V segment_distance2(V dx, float dy, float dz, glm::vec3 e,
                                                  float inv_e2) {
  const V zero{}, one = zero + 1.0f;
  const V t = vmin(vmax((dx * e.x + (dy * e.y + dz * e.z)) * inv_e2, zero), one);
  const V qx = dx - t * e.x, qy = dy - t * e.y, qz = dz - t * e.z;
  return qx * qx + qy * qy + qz * qz;
}

struct BrickJob {
  const MeshDistance* md;
  const BandTriangle* tris;
  const uint32_t* list;  // the triangles that may reach the brick, ascending
  size_t count;
  glm::ivec3 brick;
  glm::ivec3 dims;
  float band;
  float* out_distance;  // kBrickVoxels each
  int32_t* out_triangle;
};

// The band of one brick. Triangle-major, as a rasteriser: each triangle
// visits the brick rows its ball meets and computes the exact distance of W
// voxels of a row at once, branch-free (the nearer of the face, where the
// voxel projects into it, and the three edges), once a lower bound says
// some of them may get nearer. The brick's arrays stay in L1.
template <int W>
[[gnu::always_inline]] inline void band_brick_lanes(const BrickJob& job) {
  using F = typename Lanes<W>::F;
  using M = typename Lanes<W>::M;
  constexpr int B = NarrowBand::kBrick;
  constexpr int C = B / W;  // chunks per row
  static_assert(B % W == 0);
  const glm::ivec3 org = job.brick * B;
  F x[C];
  M in_grid[C];  // lanes past the grid's end never enter the band
  for (int c = 0; c < C; ++c) {
    for (int i = 0; i < W; ++i)
      x[c][i] = float(org.x + c * W + i);
    in_grid[c] = x[c] < float(job.dims.x);
  }
  F best2[B * B * C];  // squared distance so far
  M best_t[B * B * C];
  M best_in_face[B * B * C];  // whether that distance is to the face's interior
  for (int r = 0; r < B * B * C; ++r) {
    best2[r] = F{} + job.band * job.band;
    best_t[r] = M{} - 1;
    best_in_face[r] = M{};
  }
  for (size_t k = 0; k < job.count; ++k) {
    const uint32_t t = job.list[k];
    const BandTriangle& bt = job.tris[t];
    const glm::ivec3 ilo = glm::max(bt.lo, org), ihi = glm::min(bt.hi, org + (B - 1));
    const float ball = job.band + bt.radius;
    // Distance along x from the ball's centre to the voxels the triangle's box holds.
    const float gap_x = std::max({float(ilo.x) - bt.centre.x, bt.centre.x - float(ihi.x), 0.0f});
    F ax[C], hx[C], ux[C], vx[C];
    for (int c = 0; c < C; ++c) {
      ax[c] = x[c] - bt.a.x;
      hx[c] = ax[c] * bt.normal.x;
      ux[c] = ax[c] * bt.dual_ab.x;
      vx[c] = ax[c] * bt.dual_ac.x;
    }
    for (int z = ilo.z; z <= ihi.z; ++z)
      for (int y = ilo.y; y <= ihi.y; ++y) {
        const float cy = float(y) - bt.centre.y, cz = float(z) - bt.centre.z;
        if (cy * cy + cz * cz + gap_x * gap_x >= ball * ball) continue;
        const float ay = float(y) - bt.a.y, az = float(z) - bt.a.z;
        const float hyz = ay * bt.normal.y + az * bt.normal.z;
        const float uyz = ay * bt.dual_ab.y + az * bt.dual_ab.z;
        const float vyz = ay * bt.dual_ac.y + az * bt.dual_ac.z;
        for (int c = 0; c < C; ++c) {
          const int r = ((z - org.z) * B + (y - org.y)) * C + c;
          const F h = hx[c] + hyz, u = ux[c] + uyz, v = vx[c] + vyz;
          // A lower bound of the distance: the plane distance h and, in the
          // plane, how far the projection lies beyond the farthest edge
          // line. It is exact unless the nearest point is a corner, so most
          // chunks that cannot improve any voxel end here.
          const F beyond = vmax(vmax(-u * bt.height_b, -v * bt.height_c),
                                vmax((u + v - 1.0f) * bt.height_a, F{}));
          const M may_improve = h * h + beyond * beyond < best2[r];
          if (!any<W>(may_improve)) continue;
          // The exact distance: to the point u ab + v ac of the face when
          // the projection falls inside it, and to the nearest edge. Both
          // are distances to points of the triangle, so rounding can only
          // make them longer, never shorter, and the nearer one is taken.
          const M inside = (u >= 0.0f) & (v >= 0.0f) & (u + v <= bt.uv_limit);
          const F qx = ax[c] - u * bt.ab.x - v * bt.ac.x;
          const F qy = ay - u * bt.ab.y - v * bt.ac.y;
          const F qz = az - u * bt.ab.z - v * bt.ac.z;
          const F to_face = qx * qx + qy * qy + qz * qz;
          const F edges = vmin(
              vmin(segment_distance2(ax[c], ay, az, bt.ab, bt.inv_ab2),
                   segment_distance2(ax[c], ay, az, bt.ac, bt.inv_ac2)),
              segment_distance2(ax[c] - bt.ab.x, ay - bt.ab.y, az - bt.ab.z, bt.bc, bt.inv_bc2));
          const M face = inside & (to_face <= edges);
          const F d2 = face ? to_face : edges;
          // Strictly nearer only: ties keep the first triangle in ascending
          // order, the same for any thread count. Each lane also heeds its
          // own bound (which may round above d2 on a near tie), so the
          // result does not depend on the lanes computed beside it.
          const M nearer = (d2 < best2[r]) & may_improve & in_grid[c];
          best2[r] = nearer ? d2 : best2[r];
          best_t[r] = nearer ? int32_t(t) : best_t[r];
          best_in_face[r] = nearer ? face : best_in_face[r];
        }
      }
  }
  // The distance is the kernel's; the sign that of the plane distance when
  // the nearest point is inside a face (most voxels), else of the edge's or
  // corner's pseudonormal (MeshDistance; also for slivers). The chunks of a
  // row follow each other, so voxel i is lane i % W of chunk i / W.
  for (int i = 0; i < NarrowBand::kBrickVoxels; ++i) {
    const int32_t t = best_t[i / W][i % W];
    job.out_triangle[i] = t;
    if (t < 0) {
      job.out_distance[i] = kInf;
      continue;
    }
    const glm::vec3 p(voxel_in_brick(job.brick, i));
    const BandTriangle& bt = job.tris[size_t(t)];
    const bool inside = best_in_face[i / W][i % W] && bt.normal != glm::vec3(0.0f);
    const float side =
        inside ? glm::dot(p - bt.a, bt.normal) : job.md->signed_distance_to(p, uint32_t(t));
    const float d = std::sqrt(best2[i / W][i % W]);
    job.out_distance[i] = side < 0.0f ? -d : d;
  }
}

#if SCULPT_DISTANCE_AVX2
__attribute__((target("avx2"))) void band_brick_avx2(const BrickJob& job) {
  band_brick_lanes<8>(job);
}
#endif

void band_brick_baseline(const BrickJob& job) {
  band_brick_lanes<4>(job);
}

std::atomic<bool> g_avx2_band_kernel{true};

// The same arithmetic per lane either way, so both give the same band.
void band_brick(const BrickJob& job) {
#if SCULPT_DISTANCE_AVX2
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2 && g_avx2_band_kernel.load(std::memory_order_relaxed)) return band_brick_avx2(job);
#endif
  band_brick_baseline(job);
}

}  // namespace

NarrowBand mesh_narrow_band(const MeshDistance& md, glm::ivec3 dims,
                            const NarrowBandOptions& options) {
  constexpr int B = NarrowBand::kBrick;
  const Mesh& mesh = md.mesh();
  const float band = options.band;
  NarrowBand out;
  out.dims = dims;
  out.bricks = (dims + (B - 1)) / B;
  const int64_t n_bricks = voxel_count(out.bricks);
  out.slot.assign(size_t(n_bricks), -1);
  if (n_bricks == 0 || mesh.triangles.empty()) return out;
  const int64_t F = int64_t(mesh.triangles.size());

  // Not value-initialised: the workers write (and first touch) every entry.
  const std::unique_ptr<BandTriangle[]> tris(new BandTriangle[size_t(F)]);
  for_chunks(
      F, [&](int64_t t) { tris[size_t(t)] = band_triangle(mesh, uint32_t(t), band, dims); },
      options.threads);

  // Bin the triangles to the bricks their band reaches (a counting sort:
  // count per chunk and brick, then every chunk writes its own range), so
  // every brick's list is in ascending triangle order whatever the number
  // of threads.
  std::vector<uint32_t> counts(size_t(kChunks * n_bricks), 0);
  parallel_for(
      kChunks,
      [&](int64_t c) {
        uint32_t* count = counts.data() + c * n_bricks;
        for (int64_t t = F * c / kChunks; t < F * (c + 1) / kChunks; ++t)
          for_each_brick(tris[size_t(t)], band, out.bricks, [&](int64_t b) { ++count[b]; });
      },
      options.threads);
  std::vector<size_t> first(size_t(n_bricks) + 1, 0);  // each brick's range in `lists`
  for (int64_t b = 0; b < n_bricks; ++b) {
    size_t sum = first[size_t(b)];
    for (int c = 0; c < kChunks; ++c) {
      const uint32_t n = counts[size_t(c * n_bricks + b)];
      counts[size_t(c * n_bricks + b)] = uint32_t(sum - first[size_t(b)]);  // chunk's offset
      sum += n;
    }
    first[size_t(b) + 1] = sum;
    if (sum > first[size_t(b)]) {
      out.slot[size_t(b)] = int32_t(out.slot_brick.size());
      out.slot_brick.push_back(int32_t(b));
    }
  }
  std::vector<uint32_t> lists(first.back());
  parallel_for(
      kChunks,
      [&](int64_t c) {
        uint32_t* offset = counts.data() + c * n_bricks;
        for (int64_t t = F * c / kChunks; t < F * (c + 1) / kChunks; ++t)
          for_each_brick(tris[size_t(t)], band, out.bricks,
                         [&](int64_t b) { lists[first[size_t(b)] + offset[b]++] = uint32_t(t); });
      },
      options.threads);

  const size_t slots = out.slot_brick.size();
  out.distance.resize(slots * NarrowBand::kBrickVoxels);
  out.triangle.resize(slots * NarrowBand::kBrickVoxels);
  parallel_for(
      int64_t(slots),
      [&](int64_t s) {
        const int32_t b = out.slot_brick[size_t(s)];
        const glm::ivec3 brick(b % out.bricks.x, (b / out.bricks.x) % out.bricks.y,
                               b / (out.bricks.x * out.bricks.y));
        band_brick(BrickJob{&md, tris.get(), lists.data() + first[size_t(b)],
                            first[size_t(b) + 1] - first[size_t(b)], brick, dims, band,
                            out.distance.data() + size_t(s) * NarrowBand::kBrickVoxels,
                            out.triangle.data() + size_t(s) * NarrowBand::kBrickVoxels});
      },
      options.threads);
  return out;
}

bool use_avx2_band_kernel(bool enabled) {
  return g_avx2_band_kernel.exchange(enabled, std::memory_order_relaxed);
}

float NarrowBand::distance_at(int x, int y, int z) const {
  const int64_t i = value_index(x, y, z);
  return i < 0 ? kInf : distance[size_t(i)];
}

int32_t NarrowBand::triangle_at(int x, int y, int z) const {
  const int64_t i = value_index(x, y, z);
  return i < 0 ? -1 : triangle[size_t(i)];
}

namespace {

// Fills a dense grid from the bricks, one z slice per task.
template <class T>
DenseGrid<T> densify(const NarrowBand& nb, const std::vector<T>& values, T outside, int threads) {
  DenseGrid<T> out(nb.dims, outside);
  parallel_for(
      nb.dims.z,
      [&](int64_t z) {
        for (int y = 0; y < nb.dims.y; ++y)
          for (int x = 0; x < nb.dims.x; ++x) {
            const int64_t i = nb.value_index(x, y, int(z));
            if (i >= 0) out.at(x, y, int(z)) = values[size_t(i)];
          }
      },
      threads);
  return out;
}

}  // namespace

DenseGrid<float> NarrowBand::dense_distance(int threads) const {
  return densify(*this, distance, std::numeric_limits<float>::infinity(), threads);
}

DenseGrid<int32_t> NarrowBand::dense_triangle(int threads) const {
  return densify(*this, triangle, int32_t(-1), threads);
}

}  // namespace sculpt::core
