#include "sculpt/core/haptics/distance_patch.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>
#include <tuple>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "nearest_seed.h"
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

Box DistancePatch::seed_box() const {
  // A seed within `reach` of a value lies on an edge whose ends are within
  // reach + 1 (chessboard) of it.
  return grown(box(), reach_ + 1);
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
  seeds_.clear();
  find_seeds(seed_box(), seeds_);
  compute(box());
  ++snapshot_.version;
}

namespace {

// The order seeds are offered in (z, y, axis, x of the edge): ties between
// equally near seeds go to the first, so the order is part of every value.
bool ordered_before(const glm::ivec3& a_edge, int a_axis, const glm::ivec3& b_edge, int b_axis) {
  return std::tie(a_edge.z, a_edge.y, a_axis, a_edge.x) <
         std::tie(b_edge.z, b_edge.y, b_axis, b_edge.x);
}

// Whether both ends of the edge from `edge` along `axis` lie in `box`.
bool edge_inside(glm::ivec3 edge, int axis, const Box& box) {
  glm::ivec3 end = edge;
  end[axis] += 1;
  return box.contains(edge) && box.contains(end);
}

// The voxels a seed on the edge from `edge` may be offered to: the bounding
// box of the ball around floor(point), which is the edge's lower end or, when
// the crossing rounds up to the next voxel, the one above it.
Box reach_box(glm::ivec3 edge, int reach) {
  return Box{edge - reach + 1, edge + reach + 2};
}

}  // namespace

void DistancePatch::refresh(const Volume& volume, const Box& changed) {
  refresh_boxes(volume, std::span(&changed, 1));
}

void DistancePatch::refresh_bricks(const Volume& volume, std::span<const glm::ivec3> bricks) {
  // Brick by brick: the bounding box of an L of bricks holds others, which
  // would be decoded for nothing.
  brick_boxes_.clear();
  for (const glm::ivec3 b : bricks)
    brick_boxes_.push_back(volume.brick_box(b));
  refresh_boxes(volume, brick_boxes_);
}

void DistancePatch::refresh_boxes(const Volume& volume, std::span<const Box> changed) {
  if (snapshot_.empty()) return;
  // Only the voxels whose density really changed count: a dab's box is
  // mostly material it left alone.
  flipped_.clear();
  Box differs;
  for (const Box& box : changed) {
    const Box one = read_density(volume, box, &flipped_);
    if (one.empty()) continue;
    differs = hull(differs, one);
  }
  if (differs.empty()) {
    last_computed_ = 0;
    return;
  }
  // A seed depends on the density at its edge's ends and their neighbours:
  // the seeds on the edges with both ends in `rescan` are found again, the
  // others stand.
  const Box rescan = intersect(grown(differs, 2), seed_box());
  found_.clear();
  find_seeds(rescan, found_);

  // A value can change only if it changed side or a seed offered to it
  // appeared, went or moved: those are marked stale. Merging the seeds held
  // with the ones found keeps the order.
  stale_.reset(box());
  for (const Box& run : flipped_)
    stale_.mark(run);
  // Seeds of the planes before and after the rescan stand as they are and
  // are copied whole; only those between are compared one by one.
  const auto z_below = [](const Seed& s, int z) { return s.edge.z < z; };
  const size_t first =
      size_t(std::lower_bound(seeds_.begin(), seeds_.end(), rescan.lo.z, z_below) - seeds_.begin());
  const size_t last =
      size_t(std::lower_bound(seeds_.begin(), seeds_.end(), rescan.hi.z, z_below) - seeds_.begin());
  merged_.assign(seeds_.begin(), seeds_.begin() + ptrdiff_t(first));
  size_t i = first, j = 0;
  while (i < last || j < found_.size()) {
    const Seed* held = i < last ? &seeds_[i] : nullptr;
    const Seed* found = j < found_.size() ? &found_[j] : nullptr;
    if (held && found && held->edge == found->edge && held->axis == found->axis) {
      if (held->point != found->point || held->normal != found->normal)
        stale_.mark(reach_box(held->edge, reach_));  // moved (on the same edge)
      merged_.push_back(*found);
      ++i, ++j;
    } else if (held &&
               (!found || ordered_before(held->edge, held->axis, found->edge, found->axis))) {
      if (edge_inside(held->edge, held->axis, rescan)) {
        stale_.mark(reach_box(held->edge, reach_));  // gone
      } else {
        merged_.push_back(*held);
      }
      ++i;
    } else {
      stale_.mark(reach_box(found->edge, reach_));  // new
      merged_.push_back(*found);
      ++j;
    }
  }
  merged_.insert(merged_.end(), seeds_.begin() + ptrdiff_t(last), seeds_.end());
  seeds_.swap(merged_);
  stale_.finish();
  compute(stale_.bounds(), &stale_);
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
    (void)read_density(volume, slabs[size_t(i)]);
  // The seeds: those still inside stay; those of the edges the move
  // brought in are found (an edge with an end in a new slab has the other
  // within a voxel of it) and merged in order.
  const Box old_seed_box = grown(old_box, reach_ + 1);
  std::erase_if(seeds_, [&](const Seed& s) { return !edge_inside(s.edge, s.axis, seed_box()); });
  found_.clear();
  std::array<Box, 3> scans;
  const int seed_slabs = uncovered_slabs(seed_box(), old_seed_box, scans);
  for (int i = 0; i < seed_slabs; ++i) {
    scans[size_t(i)] = intersect(grown(scans[size_t(i)], 1), seed_box());
    const size_t before = found_.size();
    find_seeds(scans[size_t(i)], found_);
    // Edges found before (both ends in the old box or an earlier scan) go.
    const auto seen = [&](const Seed& s) {
      if (edge_inside(s.edge, s.axis, old_seed_box)) return true;
      for (int j = 0; j < i; ++j)
        if (edge_inside(s.edge, s.axis, scans[size_t(j)])) return true;
      return false;
    };
    found_.erase(std::remove_if(found_.begin() + ptrdiff_t(before), found_.end(), seen),
                 found_.end());
  }
  const auto ordered = [](const Seed& a, const Seed& b) {
    return ordered_before(a.edge, a.axis, b.edge, b.axis);
  };
  std::sort(found_.begin(), found_.end(), ordered);
  merged_.resize(seeds_.size() + found_.size());
  std::merge(seeds_.begin(), seeds_.end(), found_.begin(), found_.end(), merged_.begin(), ordered);
  seeds_.swap(merged_);
  int64_t computed = 0;
  const int value_slabs = uncovered_slabs(box(), old_box, slabs);
  for (int i = 0; i < value_slabs; ++i) {
    compute(slabs[size_t(i)]);
    computed += last_computed_;
  }
  last_computed_ = computed;
  ++snapshot_.version;
}

Box DistancePatch::read_density(const Volume& volume, const Box& region,
                                std::vector<Box>* flipped) {
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
      // Inside is the top bit; each run of voxels that changed side is one box.
      for (int x = first; flipped && x <= last; ++x) {
        if (((to[x] ^ from[x]) & 0x80) == 0) continue;
        int end = x + 1;
        while (end <= last && ((to[end] ^ from[end]) & 0x80) != 0)
          ++end;
        flipped->push_back(Box{{r.lo.x + x, y, z}, {r.lo.x + end, y + 1, z + 1}});
        x = end;
      }
      std::memcpy(to, from, size_t(n));
    }
  return changed.empty() ? Box{} : changed;
}

void DistancePatch::compute(const Box& region, const CellMarks* stale) {
  last_computed_ = 0;
  if (region.empty()) return;
  const int reach = reach_;
  // The seeds offered: those reaching `region` (and, with `stale`, a marked
  // cell), in order; the search breaks ties by that order, so they go the
  // same way whatever region is computed.
  offered_.clear();
  seed_points_.clear();
  // Seeds are in z order: only those of the planes within reach are looked at.
  const auto z_below = [](const Seed& s, int z) { return s.edge.z < z; };
  const auto from =
      std::lower_bound(seeds_.begin(), seeds_.end(), region.lo.z - reach - 1, z_below);
  const auto to = std::lower_bound(from, seeds_.end(), region.hi.z + reach, z_below);
  for (const Seed& s : std::span(from, to)) {
    const Box reached = intersect(reach_box(s.edge, reach), region);
    if (reached.empty() || (stale && !stale->any(reached))) continue;
    offered_.push_back(s);
    seed_points_.push_back(s.point);
  }
  if (offered_.size() > kMaxSeeds) {
    // More than one search tells apart (dense, noisy material in a large
    // patch): halve the region along its longest side.
    const glm::ivec3 rs = region.size();
    const int a = rs.x >= rs.y && rs.x >= rs.z ? 0 : rs.y >= rs.z ? 1 : 2;
    Box first = region, second = region;
    first.hi[a] = second.lo[a] = region.lo[a] + rs[a] / 2;
    compute(first, stale);
    const int64_t done = last_computed_;
    compute(second, stale);
    last_computed_ += done;
    return;
  }

  const glm::ivec3 rs = region.size();
  const size_t stride = size_t(rs.x) + kRowPadding;
  best_key_.assign(stride * size_t(rs.y) * size_t(rs.z), unreached_key(reach));
  // The values are split in z among the threads; each offers every seed to
  // its own slab, so the split never changes a value.
  const int slabs = std::max(1, std::min(options_.threads, rs.z / 8));
  std::vector<int64_t> written(size_t(slabs), 0);
  const auto slab = [&](int64_t k) {
    Box clip = region;
    clip.lo.z = region.lo.z + int(int64_t(rs.z) * k / slabs);
    clip.hi.z = region.lo.z + int(int64_t(rs.z) * (k + 1) / slabs);
    offer_seeds(seed_points_, region, clip, stride, reach, best_key_.data());
    written[size_t(k)] = write_values(region, clip, stride, stale);
  };
  if (slabs == 1) {
    slab(0);
  } else {
    parallel_for(slabs, slab, slabs);
  }
  for (const int64_t n : written)
    last_computed_ += n;
}

int64_t DistancePatch::write_values(const Box& region, const Box& clip, size_t stride,
                                    const CellMarks* stale) {
  const glm::ivec3 rs = region.size();
  const int reach = reach_;
  // Values: the distance to the nearest seed's tangent plane, signed by the
  // voxel's own side. Where plane and side disagree (a voxel beside a sharp
  // fold) 0 is stored: an underestimate, which keeps a sphere-tracing step
  // safe. No seed within `reach` means the surface is at least clamp_vox
  // away (see build()), the bound stored there.
  const float clamp = snapshot_.clamp_vox;
  int64_t written = 0;
  for (int z = clip.lo.z; z < clip.hi.z; ++z)
    for (int y = clip.lo.y; y < clip.hi.y; ++y) {
      const uint8_t* d = &density_[local_index({clip.lo.x, y, z}, density_box_)];
      float* out = &snapshot_.phi[local_index({clip.lo.x, y, z}, box())];
      size_t i = (size_t(z - region.lo.z) * size_t(rs.y) + size_t(y - region.lo.y)) * stride;
      const uint8_t* marks = stale ? stale->row_marks(y, z) : nullptr;
      const int marks_lo = stale ? stale->box().lo.x : 0;
      for (int x = clip.lo.x; x < clip.hi.x; ++x, ++i, ++d, ++out) {
        if (marks && !marks[(x - marks_lo) >> 1]) continue;
        const bool inside = *d >= 128;
        float magnitude = clamp;
        if (const int32_t seed = seed_of_key(best_key_[i]); seed >= 0) {
          const Seed& s = offered_[size_t(seed)];
          const float plane = glm::dot(glm::vec3(float(x), float(y), float(z)) - s.point, s.normal);
          magnitude = std::clamp(inside ? -plane : plane, 0.0f, float(reach));
        }
        *out = inside ? -magnitude : magnitude;
        ++written;
      }
    }
  return written;
}

void DistancePatch::find_seeds(const Box& scan, std::vector<Seed>& out) {
  if (scan.empty()) return;
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
  const ptrdiff_t plane = ptrdiff_t(ds.x) * ds.y;
  // Seeds come row by row (z, then y), the three axes' edges of a row in
  // turn: the offers then sweep the values once, a few planes at a time.
  for (int z = scan.lo.z; z < scan.hi.z; ++z)
    for (int y = scan.lo.y; y < scan.hi.y; ++y)
      for (int a = 0; a < 3; ++a) {
        glm::ivec3 step(0);
        step[a] = 1;
        if (y + step.y >= scan.hi.y || z + step.z >= scan.hi.z) continue;
        if (!mixed(sides(y, z), sides(y + step.y, z + step.z))) continue;
        const size_t stride = a == 0 ? 1 : a == 1 ? size_t(ds.x) : size_t(plane);
        const int x_end = scan.hi.x - step.x;
        const uint8_t* row = &density_[local_index({scan.lo.x, y, z}, density_box_)];
        for (int x = scan.lo.x; x < x_end; ++x, ++row) {
          // Inside is the top bit of a density: eight edges at a time whose
          // ends agree on it are skipped in one test.
          if (x + 8 <= x_end) {
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
          const auto gradient = [&](const uint8_t* p) {
            return glm::vec3(float(p[1]) - float(p[-1]), float(p[ds.x]) - float(p[-ds.x]),
                             float(p[plane]) - float(p[-plane]));
          };
          const glm::vec3 g = 0.5f * glm::mix(gradient(row), gradient(row + stride), t);
          // The edges along the axis nearest the normal place the surface a
          // seed per column, enough for the tangent planes; the others would
          // add seeds beside those, and time, but no accuracy. Most crossings
          // fail that test by far and go before the square root (the margin
          // keeps the exact test's outcome).
          const glm::vec3 ga = glm::abs(g);
          if (ga[a] < 0.99f * std::max({ga.x, ga.y, ga.z}) && glm::dot(g, g) > 1e-6f) continue;
          const float length = glm::length(g);
          // Density falls outward; a flat gradient (a one-voxel sliver) takes
          // the edge's own direction.
          const glm::vec3 normal =
              length > 1e-3f ? -g / length : glm::vec3(step) * (d0 >= 128 ? 1.0f : -1.0f);
          const glm::vec3 m = glm::abs(normal);
          if (m[a] < std::max({m.x, m.y, m.z})) continue;
          Seed& seed = out.emplace_back();
          seed.point = glm::vec3(v) + t * glm::vec3(step);
          seed.normal = normal;
          seed.edge = v;
          seed.axis = a;
        }
      }
}

}  // namespace sculpt::core
