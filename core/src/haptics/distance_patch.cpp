#include "sculpt/core/haptics/distance_patch.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstring>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

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

constexpr uint8_t kUnreached = 255;
constexpr uint8_t kPadding = 254;

}  // namespace

int patch_edge_for_reach(float reach_vox, float band_vox) {
  // The tool's reach on both sides, the band beyond it, and as much again to
  // move before the patch has to follow.
  const float needed = 2.0f * (std::max(reach_vox, 0.0f) + band_vox) + 16.0f;
  const int edge = int(std::ceil(needed / 8.0f)) * 8;
  return std::max(48, edge);
}

DistancePatch::DistancePatch(const DistancePatchOptions& options)
    : options_(options), rings_(int(std::ceil(options.band_vox)) + 1), margin_(rings_ + 2) {
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
  snapshot_.clamp_vox = float(rings_);
  snapshot_.phi.assign(size_t(edge) * edge * edge, 0.0f);
  density_box_ = grown(box(), margin_);
  density_.assign(size_t(density_box_.voxel_count()), 0);
  read_density(volume, density_box_);
  compute(box());
  ++snapshot_.version;
}

void DistancePatch::refresh(const Volume& volume, const Box& changed) {
  if (snapshot_.empty()) return;
  const Box read = intersect(changed, density_box_);
  if (read.empty()) return;
  read_density(volume, read);
  // A value depends on the density within margin_ of it.
  compute(intersect(grown(read, margin_), box()));
  ++snapshot_.version;
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
    read_density(volume, slabs[size_t(i)]);
  int64_t computed = 0;
  const int value_slabs = uncovered_slabs(box(), old_box, slabs);
  for (int i = 0; i < value_slabs; ++i) {
    compute(slabs[size_t(i)]);
    computed += last_computed_;
  }
  last_computed_ = computed;
  ++snapshot_.version;
}

void DistancePatch::read_density(const Volume& volume, const Box& region) {
  const Box r = intersect(region, density_box_);
  if (r.empty()) return;
  const DenseGrid<uint8_t> values = volume.read(r);
  const size_t row = size_t(r.size().x);
  for (int z = r.lo.z; z < r.hi.z; ++z)
    for (int y = r.lo.y; y < r.hi.y; ++y)
      std::memcpy(&density_[local_index({r.lo.x, y, z}, density_box_)],
                  &values.values()[local_index({r.lo.x, y, z}, r)], row);
}

uint8_t DistancePatch::density(glm::ivec3 v) const {
  assert(density_box_.contains(v));
  return density_[local_index(v, density_box_)];
}

glm::vec3 DistancePatch::density_gradient(glm::ivec3 v) const {
  const auto d = [&](int dx, int dy, int dz) { return float(density(v + glm::ivec3(dx, dy, dz))); };
  return 0.5f *
         glm::vec3(d(1, 0, 0) - d(-1, 0, 0), d(0, 1, 0) - d(0, -1, 0), d(0, 0, 1) - d(0, 0, -1));
}

void DistancePatch::compute(const Box& region) {
  last_computed_ = region.voxel_count();
  if (region.empty()) return;
  const int rings = rings_;
  // Seeds within `rings` (chessboard) of a value can be its nearest; the
  // scratch grids cover them with one voxel of padding, so the ring search
  // needs no bounds checks.
  const Box search = intersect(grown(region, rings), grown(box(), rings));
  const Box padded = grown(search, 1);
  const glm::ivec3 ps = padded.size();
  const size_t cells = size_t(padded.voxel_count());
  ring_.assign(cells, kPadding);
  nearest_.resize(cells);
  for (int z = search.lo.z; z < search.hi.z; ++z)
    for (int y = search.lo.y; y < search.hi.y; ++y)
      std::memset(&ring_[local_index({search.lo.x, y, z}, padded)], kUnreached,
                  size_t(search.size().x));
  seeds_.clear();
  frontier_.clear();

  // Among seeds at equal distance the smaller point wins, so the choice does
  // not depend on the order the seeds are met in (refresh == build).
  const auto closer = [&](int32_t a, int32_t b, glm::vec3 v) {
    const glm::vec3 pa = seeds_[size_t(a)].point, pb = seeds_[size_t(b)].point;
    const glm::vec3 da = v - pa, db = v - pb;
    const float la = glm::dot(da, da), lb = glm::dot(db, db);
    if (la != lb) return la < lb;
    if (pa.x != pb.x) return pa.x < pb.x;
    if (pa.y != pb.y) return pa.y < pb.y;
    return pa.z < pb.z;
  };
  const auto offer_seed = [&](glm::ivec3 v, int32_t seed) {
    if (!search.contains(v)) return;
    const size_t l = local_index(v, padded);
    if (ring_[l] != 0) {
      ring_[l] = 0;
      nearest_[l] = seed;
      frontier_.push_back(int32_t(l));
    } else if (closer(seed, nearest_[l], glm::vec3(v))) {
      nearest_[l] = seed;
    }
  };

  // Seeds: every edge with an end in `search` whose ends lie on both sides of
  // 127.5. The trilinear density is linear along an edge, so the crossing is
  // exact; the normal is the interpolated central-difference gradient (the
  // one the renderer shades with).
  for (int a = 0; a < 3; ++a) {
    glm::ivec3 step(0);
    step[a] = 1;
    Box from = search;
    from.lo[a] -= 1;
    for (int z = from.lo.z; z < from.hi.z; ++z)
      for (int y = from.lo.y; y < from.hi.y; ++y) {
        const uint8_t* row = &density_[local_index({from.lo.x, y, z}, density_box_)];
        const size_t stride = size_t(local_index(step, Box{glm::ivec3(0), density_box_.size()}));
        for (int x = from.lo.x; x < from.hi.x; ++x, ++row) {
          const uint8_t d0 = row[0], d1 = row[stride];
          if ((d0 >= 128) == (d1 >= 128)) continue;
          const glm::ivec3 v{x, y, z};
          const float t = (float(d0) - 127.5f) / (float(d0) - float(d1));
          Seed seed;
          seed.point = glm::vec3(v) + t * glm::vec3(step);
          const glm::vec3 g = glm::mix(density_gradient(v), density_gradient(v + step), t);
          const float length = glm::length(g);
          // Density falls outward; a flat gradient (a one-voxel sliver) takes
          // the edge's own direction.
          seed.normal = length > 1e-3f ? -g / length : glm::vec3(step) * (d0 >= 128 ? 1.0f : -1.0f);
          const int32_t id = int32_t(seeds_.size());
          seeds_.push_back(seed);
          offer_seed(v, id);
          offer_seed(v + step, id);
        }
      }
  }

  // Rings: a voxel one step (26-neighbourhood) beyond the previous ring takes
  // the nearest of the seeds its neighbours there hold.
  std::array<int32_t, 26> offsets{};
  std::array<glm::ivec3, 26> steps{};
  int n = 0;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dy == 0 && dz == 0) continue;
        steps[size_t(n)] = {dx, dy, dz};
        offsets[size_t(n)] = (dz * ps.y + dy) * ps.x + dx;
        ++n;
      }
  for (int k = 1; k <= rings; ++k) {
    next_frontier_.clear();
    for (const int32_t u : frontier_) {
      const glm::ivec3 uv = padded.lo + glm::ivec3(u % ps.x, (u / ps.x) % ps.y, u / (ps.x * ps.y));
      const int32_t seed = nearest_[size_t(u)];
      for (int i = 0; i < 26; ++i) {
        const size_t w = size_t(u + offsets[size_t(i)]);
        const uint8_t r = ring_[w];
        if (r == kUnreached) {
          ring_[w] = uint8_t(k);
          nearest_[w] = seed;
          next_frontier_.push_back(int32_t(w));
        } else if (r == k && closer(seed, nearest_[w], glm::vec3(uv + steps[size_t(i)]))) {
          nearest_[w] = seed;
        }
      }
    }
    frontier_.swap(next_frontier_);
  }

  // The rings hand a seed on only from the ring before, so a voxel can miss
  // a nearer seed one of its neighbours holds: one pass over every reached
  // voxel takes the nearest of its own and its neighbours' seeds. It reads
  // the rings' choices and writes a copy, so the order does not matter.
  relaxed_ = nearest_;
  for (int z = search.lo.z; z < search.hi.z; ++z)
    for (int y = search.lo.y; y < search.hi.y; ++y)
      for (int x = search.lo.x; x < search.hi.x; ++x) {
        const glm::ivec3 v{x, y, z};
        const size_t l = local_index(v, padded);
        if (ring_[l] > rings) continue;
        int32_t best = nearest_[l];
        for (int i = 0; i < 26; ++i) {
          const size_t w = size_t(int64_t(l) + offsets[size_t(i)]);
          if (ring_[w] > rings) continue;
          if (closer(nearest_[w], best, glm::vec3(v))) best = nearest_[w];
        }
        relaxed_[l] = best;
      }
  nearest_.swap(relaxed_);

  // Values: the distance to the nearest seed's tangent plane, signed by the
  // voxel's own side. Where plane and side disagree (a voxel beside a sharp
  // fold) 0 is stored: an underestimate, which keeps a sphere-tracing step
  // safe.
  const float clamp = float(rings);
  for (int z = region.lo.z; z < region.hi.z; ++z)
    for (int y = region.lo.y; y < region.hi.y; ++y)
      for (int x = region.lo.x; x < region.hi.x; ++x) {
        const glm::ivec3 v{x, y, z};
        const bool inside = density(v) >= 128;
        const size_t l = local_index(v, padded);
        float magnitude = clamp;
        if (ring_[l] <= rings) {
          const Seed& s = seeds_[size_t(nearest_[l])];
          const float plane = glm::dot(glm::vec3(v) - s.point, s.normal);
          magnitude = std::clamp(inside ? -plane : plane, 0.0f, clamp);
        }
        snapshot_.phi[local_index(v, box())] = inside ? -magnitude : magnitude;
      }
}

}  // namespace sculpt::core
