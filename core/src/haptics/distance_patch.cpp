#include "sculpt/core/haptics/distance_patch.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

Box grown(const Box& b, int by) {
  return Box{b.lo - by, b.hi + by};
}

size_t local_index(glm::ivec3 v, const Box& box) {
  const glm::ivec3 s = box.size();
  const glm::ivec3 l = v - box.lo;
  return (size_t(l.z) * size_t(s.y) + size_t(l.y)) * size_t(s.x) + size_t(l.x);
}

// The parts of `now` that `before` does not cover, as at most three disjoint
// slabs (one per axis the box moved along).
int uncovered_slabs(Box now, const Box& before, std::array<Box, 3>& out) {
  int n = 0;
  for (int a = 0; a < 3; ++a) {
    if (now.empty()) break;
    Box slab = now;
    if (before.lo[a] > now.lo[a]) {
      slab.hi[a] = std::min(before.lo[a], now.hi[a]);
      now.lo[a] = slab.hi[a];
    } else if (before.hi[a] < now.hi[a]) {
      slab.lo[a] = std::max(before.hi[a], now.lo[a]);
      now.hi[a] = slab.lo[a];
    } else {
      continue;
    }
    if (!slab.empty()) out[n++] = slab;
  }
  return n;
}

// Copies the part of `from` (laid out over `from_box`) that `to_box` also
// covers into `to` (laid out over `to_box`), row by row.
template <class T>
void copy_overlap(const std::vector<T>& from, const Box& from_box, std::vector<T>& to,
                  const Box& to_box) {
  const Box both = intersect(from_box, to_box);
  if (both.empty()) return;
  const size_t row = size_t(both.size().x);
  for (int z = both.lo.z; z < both.hi.z; ++z)
    for (int y = both.lo.y; y < both.hi.y; ++y) {
      const glm::ivec3 v{both.lo.x, y, z};
      std::memcpy(&to[local_index(v, to_box)], &from[local_index(v, from_box)], row * sizeof(T));
    }
}

constexpr uint8_t kHasInside = 1;
constexpr uint8_t kHasOutside = 2;

// Offers each seed to the values of `region` (laid out x fastest in best_d2
// and best_seed, rows `stride` apart) within `reach` of it; a value keeps the
// nearest, and only a strictly nearer one replaces the seed it holds. Each
// row of the ball around a seed is updated over 12 values from the seed's
// reach, without branches or square roots (values out of reach fail the
// comparison with best_d2's initial reach^2; a window running past the row's
// end lands in the row's padding of kWindow): an eight- and a four-lane
// operation a row (GCC vector types; a per-row extent costs more than it
// saves); compiled twice, for AVX2 and the baseline.
constexpr int kWindow = 16;
using Floats8 = float __attribute__((vector_size(32)));
using Ints8 = int32_t __attribute__((vector_size(32)));
using Floats4 = float __attribute__((vector_size(16)));
using Ints4 = int32_t __attribute__((vector_size(16)));
constexpr Floats8 kLanes = {0, 1, 2, 3, 4, 5, 6, 7};
constexpr Floats4 kLanes4 = {0, 1, 2, 3};

inline __attribute__((always_inline)) void offer_seeds_body(const glm::vec3* points, size_t count,
                                                            const Box& region, const Box& clip,
                                                            size_t stride, int reach,
                                                            float* best_d2, int32_t* best_seed) {
  const glm::ivec3 rs = region.size();
  const float reach2 = float(reach * reach);
  for (size_t id = 0; id < count; ++id) {
    const glm::vec3 q = points[id];
    const glm::ivec3 centre = glm::ivec3(glm::floor(q));
    const glm::ivec3 lo = glm::max(centre - reach + 1, clip.lo);
    const glm::ivec3 hi = glm::min(centre + reach + 1, clip.hi);
    if (hi.x <= lo.x) continue;
    for (int z = lo.z; z < hi.z; ++z) {
      const float dz = float(z) - q.z;
      for (int y = lo.y; y < hi.y; ++y) {
        const float dy = float(y) - q.y;
        const float base = dz * dz + dy * dy;
        if (base >= reach2) continue;
        // A row within three voxels of q along x (the ball's outer rows)
        // fits one eight-value step from centre - 3; the others take eight
        // values, then four: a row of the ball spans at most 2 * reach <= 12.
        // (Offers beyond reach never win, so covering more changes nothing.)
        const bool narrow = base >= reach2 - 9.0f;
        const int x0 = narrow ? std::max(centre.x - 3, clip.lo.x) : lo.x;
        const size_t at =
            (size_t(z - region.lo.z) * size_t(rs.y) + size_t(y - region.lo.y)) * stride +
            size_t(x0 - region.lo.x);
        const float dx0 = float(x0) - q.x;
        Floats8 held;
        Ints8 seed;
        std::memcpy(&held, best_d2 + at, sizeof held);
        std::memcpy(&seed, best_seed + at, sizeof seed);
        const Floats8 dx = dx0 + kLanes;
        const Floats8 d = base + dx * dx;
        const Ints8 nearer = d < held;
        held = nearer ? d : held;
        seed = nearer ? Ints8{} + int32_t(id) : seed;
        std::memcpy(best_d2 + at, &held, sizeof held);
        std::memcpy(best_seed + at, &seed, sizeof seed);
        if (narrow) continue;
        Floats4 held4;
        Ints4 seed4;
        std::memcpy(&held4, best_d2 + at + 8, sizeof held4);
        std::memcpy(&seed4, best_seed + at + 8, sizeof seed4);
        const Floats4 dx4 = (dx0 + 8.0f) + kLanes4;
        const Floats4 d4 = base + dx4 * dx4;
        const Ints4 nearer4 = d4 < held4;
        held4 = nearer4 ? d4 : held4;
        seed4 = nearer4 ? Ints4{} + int32_t(id) : seed4;
        std::memcpy(best_d2 + at + 8, &held4, sizeof held4);
        std::memcpy(best_seed + at + 8, &seed4, sizeof seed4);
      }
    }
  }
}

// Dispatched by hand rather than with target_clones: an ifunc resolver runs
// before ThreadSanitizer's runtime is up and crashes the instrumented build.
__attribute__((target("avx2"))) void offer_seeds_avx2(const glm::vec3* points, size_t count,
                                                      const Box& region, const Box& clip,
                                                      size_t stride, int reach, float* best_d2,
                                                      int32_t* best_seed) {
  offer_seeds_body(points, count, region, clip, stride, reach, best_d2, best_seed);
}

void offer_seeds_baseline(const glm::vec3* points, size_t count, const Box& region, const Box& clip,
                          size_t stride, int reach, float* best_d2, int32_t* best_seed) {
  offer_seeds_body(points, count, region, clip, stride, reach, best_d2, best_seed);
}

void offer_seeds(const glm::vec3* points, size_t count, const Box& region, const Box& clip,
                 size_t stride, int reach, float* best_d2, int32_t* best_seed) {
  static const bool avx2 = __builtin_cpu_supports("avx2");
  (avx2 ? offer_seeds_avx2 : offer_seeds_baseline)(points, count, region, clip, stride, reach,
                                                   best_d2, best_seed);
}

// offer_seeds() for a reach beyond six voxels (a wide band, for a sphere
// tool of large radius): the same result, row by row over the exact extent.
void offer_seeds_wide(const glm::vec3* points, size_t count, const Box& region, const Box& clip,
                      size_t stride, int reach, float* best_d2, int32_t* best_seed) {
  const glm::ivec3 rs = region.size();
  const float reach2 = float(reach * reach);
  for (size_t id = 0; id < count; ++id) {
    const glm::vec3 q = points[id];
    const glm::ivec3 centre = glm::ivec3(glm::floor(q));
    const glm::ivec3 lo = glm::max(centre - reach + 1, clip.lo);
    const glm::ivec3 hi = glm::min(centre + reach + 1, clip.hi);
    for (int z = lo.z; z < hi.z; ++z)
      for (int y = lo.y; y < hi.y; ++y) {
        const float base =
            (float(z) - q.z) * (float(z) - q.z) + (float(y) - q.y) * (float(y) - q.y);
        if (base >= reach2) continue;
        const size_t row =
            (size_t(z - region.lo.z) * size_t(rs.y) + size_t(y - region.lo.y)) * stride;
        for (int x = lo.x; x < hi.x; ++x) {
          const float dx = float(x) - q.x;
          const float d = base + dx * dx;
          const size_t i = row + size_t(x - region.lo.x);
          if (d < best_d2[i]) {
            best_d2[i] = d;
            best_seed[i] = int32_t(id);
          }
        }
      }
  }
}

}  // namespace

float band_for_sphere(float radius_vox) {
  return std::max(4.0f, std::ceil(radius_vox) + 3.0f);
}

int patch_edge_for_reach(float reach_vox, float band_vox) {
  // The tool's reach on both sides, the band beyond it, and as much again to
  // move before the patch has to follow.
  const float needed = 2.0f * (std::max(reach_vox, 0.0f) + band_vox) + 16.0f;
  const int edge = int(std::ceil(needed / 8.0f)) * 8;
  return std::max(48, edge);
}

DistancePatch::DistancePatch(const DistancePatchOptions& options)
    : options_(options),
      // A voxel in the band has a seed within its distance plus the farthest
      // a surface point lies from a crossing on its cell's edges (0.87: the
      // cell's half diagonal, for a smooth surface).
      reach_(int(std::ceil(options.band_vox + 0.87f))),
      margin_(reach_ + 2) {
  assert(options.edge >= 8 && options.band_vox > 0.0f);
}

Box DistancePatch::box() const {
  return Box{snapshot_.origin, snapshot_.origin + snapshot_.edge};
}

glm::vec3 DistancePatch::centre() const {
  return glm::vec3(snapshot_.origin) + 0.5f * float(snapshot_.edge - 1);
}

bool DistancePatch::off_centre(glm::vec3 p) const {
  if (snapshot_.empty()) return true;
  const glm::vec3 d = glm::abs(p - centre());
  return std::max({d.x, d.y, d.z}) > float(options_.edge) / 8.0f;
}

void DistancePatch::build(const Volume& volume, glm::vec3 centre_vox) {
  const int edge = options_.edge;
  snapshot_.origin = glm::ivec3(glm::floor(centre_vox)) - edge / 2;
  snapshot_.edge = edge;
  snapshot_.band_vox = options_.band_vox;
  // A cell the surface crosses has a crossing within its diagonal (sqrt 3),
  // though not always on an edge that gives a seed: then one in the next
  // cell along the normal does (one voxel more).
  snapshot_.clamp_vox = float(reach_) - std::sqrt(3.0f) - 1.0f;
  snapshot_.phi.assign(size_t(edge) * edge * edge, 0.0f);
  density_box_ = grown(box(), margin_);
  density_.assign(size_t(density_box_.voxel_count()), 0);
  (void)read_density(volume, density_box_);
  compute(box());
  ++snapshot_.version;
}

void DistancePatch::refresh(const Volume& volume, const Box& changed) {
  if (snapshot_.empty()) return;
  // Only the voxels whose density really changed count: a dab's box is
  // mostly material it left alone.
  const Box differs = read_density(volume, changed);
  if (differs.empty()) {
    last_computed_ = 0;
    return;
  }
  // A value depends on the density within margin_ of it.
  compute(intersect(grown(differs, margin_), box()));
  ++snapshot_.version;
}

void DistancePatch::refresh_bricks(const Volume& volume, std::span<const glm::ivec3> bricks) {
  if (bricks.empty()) return;
  Box all = volume.brick_box(bricks.front());
  for (const glm::ivec3 b : bricks) {
    const Box one = volume.brick_box(b);
    all = Box{glm::min(all.lo, one.lo), glm::max(all.hi, one.hi)};
  }
  refresh(volume, all);
}

void DistancePatch::recentre(const Volume& volume, glm::vec3 centre_vox) {
  const glm::ivec3 origin = glm::ivec3(glm::floor(centre_vox)) - options_.edge / 2;
  if (snapshot_.empty() || glm::any(glm::greaterThanEqual(glm::abs(origin - snapshot_.origin),
                                                          glm::ivec3(options_.edge)))) {
    build(volume, centre_vox);
    return;
  }
  if (origin == snapshot_.origin) return;
  const Box old_box = box(), old_density_box = density_box_;
  snapshot_.origin = origin;
  density_box_ = grown(box(), margin_);

  // Keep what both placements cover, then fill in the rest.
  std::vector<float> phi(snapshot_.phi.size());
  copy_overlap(snapshot_.phi, old_box, phi, box());
  snapshot_.phi.swap(phi);
  std::vector<uint8_t> density(density_.size());
  copy_overlap(density_, old_density_box, density, density_box_);
  density_.swap(density);

  std::array<Box, 3> slabs;
  const int density_slabs = uncovered_slabs(density_box_, old_density_box, slabs);
  for (int i = 0; i < density_slabs; ++i)
    (void)read_density(volume, slabs[size_t(i)]);
  int64_t computed = 0;
  const int value_slabs = uncovered_slabs(box(), old_box, slabs);
  for (int i = 0; i < value_slabs; ++i) {
    compute(slabs[size_t(i)]);
    computed += last_computed_;
  }
  last_computed_ = computed;
  ++snapshot_.version;
}

Box DistancePatch::read_density(const Volume& volume, const Box& region) {
  const Box r = intersect(region, density_box_);
  Box changed{glm::ivec3(std::numeric_limits<int>::max()),
              glm::ivec3(std::numeric_limits<int>::min())};
  if (r.empty()) return Box{};
  const DenseGrid<uint8_t> values = volume.read(r);
  const int n = r.size().x;
  for (int z = r.lo.z; z < r.hi.z; ++z)
    for (int y = r.lo.y; y < r.hi.y; ++y) {
      uint8_t* to = &density_[local_index({r.lo.x, y, z}, density_box_)];
      const uint8_t* from = &values.values()[local_index({r.lo.x, y, z}, r)];
      if (std::memcmp(to, from, size_t(n)) == 0) continue;
      int first = 0, last = n - 1;
      while (to[first] == from[first])
        ++first;
      while (to[last] == from[last])
        --last;
      changed.lo = glm::min(changed.lo, glm::ivec3(r.lo.x + first, y, z));
      changed.hi = glm::max(changed.hi, glm::ivec3(r.lo.x + last + 1, y + 1, z + 1));
      std::memcpy(to, from, size_t(n));
    }
  return changed.empty() ? Box{} : changed;
}

void DistancePatch::compute(const Box& region) {
  last_computed_ = region.voxel_count();
  if (region.empty()) return;
  const int reach = reach_;
  // A seed within `reach` of a value lies on an edge whose ends are within
  // reach + 1 (chessboard) of it; these are all the edges looked at.
  const Box scan = intersect(grown(region, reach + 1), grown(box(), reach + 1));
  find_seeds(scan);

  // Each seed offers itself to the values of `region` in the ball of radius
  // `reach` around it; a value keeps the nearest. Seeds come in a fixed order
  // (axis, then z, y, x of the edge) and only a strictly nearer one replaces
  // the one held, so ties go the same way whatever region is computed.
  const glm::ivec3 rs = region.size();
  const size_t stride = size_t(rs.x) + kWindow;
  const size_t count = stride * size_t(rs.y) * size_t(rs.z);
  best_d2_.assign(count, float(reach * reach));
  best_seed_.assign(count, -1);
  seed_points_.resize(seeds_.size());
  for (size_t i = 0; i < seeds_.size(); ++i)
    seed_points_[i] = seeds_[i].point;
  // The values are split in z among the threads; each offers every seed to
  // its own slab, in the same order, so the split never changes a value.
  const int slabs = std::max(1, std::min(options_.threads, rs.z / 8));
  const auto slab = [&](int64_t k) {
    Box clip = region;
    clip.lo.z = region.lo.z + int(int64_t(rs.z) * k / slabs);
    clip.hi.z = region.lo.z + int(int64_t(rs.z) * (k + 1) / slabs);
    if (2 * reach <= 12) {
      offer_seeds(seed_points_.data(), seed_points_.size(), region, clip, stride, reach,
                  best_d2_.data(), best_seed_.data());
    } else {
      offer_seeds_wide(seed_points_.data(), seed_points_.size(), region, clip, stride, reach,
                       best_d2_.data(), best_seed_.data());
    }
    write_values(region, clip, stride);
  };
  if (slabs == 1) {
    slab(0);
  } else {
    parallel_for(slabs, slab, slabs);
  }
}

void DistancePatch::write_values(const Box& region, const Box& clip, size_t stride) {
  const glm::ivec3 rs = region.size();
  const int reach = reach_;
  // Values: the distance to the nearest seed's tangent plane, signed by the
  // voxel's own side. Where plane and side disagree (a voxel beside a sharp
  // fold) 0 is stored: an underestimate, which keeps a sphere-tracing step
  // safe. No seed within `reach` means the surface is at least clamp_vox
  // away (see build()), the bound stored there.
  const float clamp = snapshot_.clamp_vox;
  for (int z = clip.lo.z; z < clip.hi.z; ++z)
    for (int y = clip.lo.y; y < clip.hi.y; ++y) {
      const uint8_t* d = &density_[local_index({clip.lo.x, y, z}, density_box_)];
      float* out = &snapshot_.phi[local_index({clip.lo.x, y, z}, box())];
      size_t i = (size_t(z - region.lo.z) * size_t(rs.y) + size_t(y - region.lo.y)) * stride;
      for (int x = clip.lo.x; x < clip.hi.x; ++x, ++i, ++d, ++out) {
        const bool inside = *d >= 128;
        float magnitude = clamp;
        if (best_seed_[i] >= 0) {
          const Seed& s = seeds_[size_t(best_seed_[i])];
          const float plane = glm::dot(glm::vec3(float(x), float(y), float(z)) - s.point, s.normal);
          magnitude = std::clamp(inside ? -plane : plane, 0.0f, float(reach));
        }
        *out = inside ? -magnitude : magnitude;
      }
    }
}

void DistancePatch::find_seeds(const Box& scan) {
  seeds_.clear();
  // Which rows (along x) of `scan` hold inside and outside voxels: an edge
  // between two rows can cross the surface only if they are not all on one
  // and the same side, which skips most of the patch at once.
  const glm::ivec3 ss = scan.size();
  row_sides_.assign(size_t(ss.y) * size_t(ss.z), 0);
  for (int z = scan.lo.z; z < scan.hi.z; ++z)
    for (int y = scan.lo.y; y < scan.hi.y; ++y) {
      const uint8_t* row = &density_[local_index({scan.lo.x, y, z}, density_box_)];
      uint8_t lo = 255, hi = 0;
      for (int x = 0; x < ss.x; ++x) {
        lo = std::min(lo, row[x]);
        hi = std::max(hi, row[x]);
      }
      row_sides_[size_t(z - scan.lo.z) * size_t(ss.y) + size_t(y - scan.lo.y)] =
          uint8_t((hi >= 128 ? kHasInside : 0) | (lo < 128 ? kHasOutside : 0));
    }
  const auto sides = [&](int y, int z) {
    return row_sides_[size_t(z - scan.lo.z) * size_t(ss.y) + size_t(y - scan.lo.y)];
  };
  const auto mixed = [](uint8_t a, uint8_t b) {
    return ((a | b) & kHasInside) && ((a | b) & kHasOutside);
  };

  const glm::ivec3 ds = density_box_.size();
  for (int a = 0; a < 3; ++a) {
    glm::ivec3 step(0);
    step[a] = 1;
    const ptrdiff_t plane = ptrdiff_t(ds.x) * ds.y;
    const size_t stride = a == 0 ? 1 : a == 1 ? size_t(ds.x) : size_t(plane);
    Box from = scan;
    from.hi[a] -= 1;
    for (int z = from.lo.z; z < from.hi.z; ++z)
      for (int y = from.lo.y; y < from.hi.y; ++y) {
        if (!mixed(sides(y, z), sides(y + step.y, z + step.z))) continue;
        const uint8_t* row = &density_[local_index({from.lo.x, y, z}, density_box_)];
        for (int x = from.lo.x; x < from.hi.x; ++x, ++row) {
          // Inside is the top bit of a density: eight edges at a time whose
          // ends agree on it are skipped in one test.
          if (x + 8 <= from.hi.x) {
            uint64_t here, there;
            std::memcpy(&here, row, 8);
            std::memcpy(&there, row + stride, 8);
            if (((here ^ there) & 0x8080808080808080ull) == 0) {
              x += 7;
              row += 7;
              continue;
            }
          }
          const uint8_t d0 = row[0], d1 = row[stride];
          if ((d0 >= 128) == (d1 >= 128)) continue;
          const glm::ivec3 v{x, y, z};
          // The trilinear density is linear along an edge: the crossing is
          // exact. The normal is the interpolated central-difference
          // gradient (the one the renderer shades with).
          const float t = (float(d0) - 127.5f) / (float(d0) - float(d1));
          Seed seed;
          seed.point = glm::vec3(v) + t * glm::vec3(step);
          const auto gradient = [&](const uint8_t* p) {
            return glm::vec3(float(p[1]) - float(p[-1]), float(p[ds.x]) - float(p[-ds.x]),
                             float(p[plane]) - float(p[-plane]));
          };
          const glm::vec3 g = 0.5f * glm::mix(gradient(row), gradient(row + stride), t);
          const float length = glm::length(g);
          // Density falls outward; a flat gradient (a one-voxel sliver) takes
          // the edge's own direction.
          seed.normal = length > 1e-3f ? -g / length : glm::vec3(step) * (d0 >= 128 ? 1.0f : -1.0f);
          // The edges along the axis nearest the normal (or nearly as near)
          // place the surface a seed per column, enough for the tangent
          // planes; the others add seeds beside those, and time, but little
          // accuracy.
          const glm::vec3 m = glm::abs(seed.normal);
          if (m[a] < 0.9f * std::max({m.x, m.y, m.z})) continue;
          seeds_.push_back(seed);
        }
      }
  }
}

}  // namespace sculpt::core
