#include "nearest_seed.h"

#include <algorithm>
#include <cstring>

#include <glm/common.hpp>

namespace sculpt::core {
namespace {

constexpr uint32_t kNumberMask = uint32_t(kMaxSeeds);

// The fixed-point scale of a key's distance part: reach^2 maps to 32767
// above the number's 16 bits (so below 2^31: the conversion is signed).
float distance_scale(float reach2) {
  return 32767.0f * 65536.0f / reach2;
}

inline uint32_t make_key(float scaled_d2, float limit, uint32_t number) {
  return (uint32_t(int32_t(std::min(scaled_d2, limit))) & ~kNumberMask) | number;
}

using Floats = float __attribute__((vector_size(64)));
using Keys = uint32_t __attribute__((vector_size(64)));
constexpr Floats kLanes = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
constexpr int kLaneCount = 16;
// Seeds come in runs along a row of the patch: up to kGroup neighbours take
// their minimum first and share each row's load and store.
constexpr size_t kGroup = 4;

// make_key() sixteen times. (By reference: a 64-byte vector passed by value
// changes with the target.)
inline __attribute__((always_inline)) void make_keys(const Floats& scaled_d2, float limit,
                                                     uint32_t number, Keys& keys) {
  using Ints = int32_t __attribute__((vector_size(64)));
  const Floats kept = scaled_d2 < limit ? scaled_d2 : Floats{} + limit;
  keys = (Keys)__builtin_convertvector(kept, Ints);
  keys = (keys & ~kNumberMask) | number;
}

// A row of a seed's ball spans at most 2 * reach <= 16 values: one step of
// sixteen lanes from the group's left end covers every member whose centre
// lies within 16 - 2 * reach of it. Lanes out of reach make the unreached
// key's distance and a larger number, so never win.
inline __attribute__((always_inline)) void offer_body(std::span<const glm::vec3> points,
                                                      const Box& region, const Box& clip,
                                                      size_t stride, int reach, uint32_t* keys) {
  const glm::ivec3 rs = region.size();
  const float reach2 = float(reach * reach);
  const float scale = distance_scale(reach2), limit = reach2 * scale;
  const int spread = kLaneCount - 2 * reach;
  const size_t count = points.size();
  for (size_t first = 0; first < count;) {
    glm::ivec3 glo = glm::ivec3(glm::floor(points[first])), ghi = glo;
    size_t end = first + 1;
    while (end < count && end - first < kGroup) {
      const glm::ivec3 c = glm::ivec3(glm::floor(points[end]));
      const glm::ivec3 lo_next = glm::min(glo, c), hi_next = glm::max(ghi, c);
      if (hi_next.x - lo_next.x > spread || hi_next.y - lo_next.y > 1 ||
          hi_next.z - lo_next.z > 1)
        break;
      glo = lo_next, ghi = hi_next, ++end;
    }
    const size_t n = end - first;
    const glm::vec3* q = &points[first];
    const uint32_t number = uint32_t(first) + 1;
    first = end;
    const glm::ivec3 lo = glm::max(glo - reach + 1, clip.lo);
    const glm::ivec3 hi = glm::min(ghi + reach + 1, clip.hi);
    if (hi.x <= lo.x || hi.y <= lo.y || hi.z <= lo.z) continue;
    Floats dx2[kGroup];
    for (size_t m = 0; m < n; ++m) {
      const Floats dx = (float(lo.x) - q[m].x) + kLanes;
      dx2[m] = dx * dx * scale;
    }
    for (int z = lo.z; z < hi.z; ++z)
      for (int y = lo.y; y < hi.y; ++y) {
        float base[kGroup];
        bool reached = false;
        for (size_t m = 0; m < n; ++m) {
          const float dz = float(z) - q[m].z, dy = float(y) - q[m].y;
          base[m] = dz * dz + dy * dy;
          reached |= base[m] < reach2;
          base[m] *= scale;
        }
        if (!reached) continue;
        Keys best, k;
        make_keys(base[0] + dx2[0], limit, number, best);
        for (size_t m = 1; m < n; ++m) {
          make_keys(base[m] + dx2[m], limit, number + uint32_t(m), k);
          best = k < best ? k : best;
        }
        uint32_t* row = keys + (size_t(z - region.lo.z) * size_t(rs.y) + size_t(y - region.lo.y)) *
                                   stride +
                        size_t(lo.x - region.lo.x);
        Keys held;
        std::memcpy(&held, row, sizeof held);
        held = best < held ? best : held;
        std::memcpy(row, &held, sizeof held);
      }
  }
}

// Dispatched by hand rather than with target_clones: an ifunc resolver runs
// before ThreadSanitizer's runtime is up and crashes the instrumented build.
__attribute__((target("avx512f"))) void offer_avx512(std::span<const glm::vec3> points,
                                                    const Box& region, const Box& clip,
                                                    size_t stride, int reach, uint32_t* keys) {
  offer_body(points, region, clip, stride, reach, keys);
}

__attribute__((target("avx2"))) void offer_avx2(std::span<const glm::vec3> points,
                                                const Box& region, const Box& clip, size_t stride,
                                                int reach, uint32_t* keys) {
  offer_body(points, region, clip, stride, reach, keys);
}

void offer_baseline(std::span<const glm::vec3> points, const Box& region, const Box& clip,
                    size_t stride, int reach, uint32_t* keys) {
  offer_body(points, region, clip, stride, reach, keys);
}

// A reach beyond eight voxels (a wide band, for a sphere tool of large
// radius): the same keys, value by value over each row's extent.
void offer_wide(std::span<const glm::vec3> points, const Box& region, const Box& clip,
                size_t stride, int reach, uint32_t* keys) {
  const glm::ivec3 rs = region.size();
  const float reach2 = float(reach * reach);
  const float scale = distance_scale(reach2), limit = reach2 * scale;
  for (size_t id = 0; id < points.size(); ++id) {
    const glm::vec3 q = points[id];
    const glm::ivec3 centre = glm::ivec3(glm::floor(q));
    const glm::ivec3 lo = glm::max(centre - reach + 1, clip.lo);
    const glm::ivec3 hi = glm::min(centre + reach + 1, clip.hi);
    for (int z = lo.z; z < hi.z; ++z)
      for (int y = lo.y; y < hi.y; ++y) {
        const float base =
            (float(z) - q.z) * (float(z) - q.z) + (float(y) - q.y) * (float(y) - q.y);
        if (base >= reach2) continue;
        const float scaled_base = base * scale;
        uint32_t* row =
            keys + (size_t(z - region.lo.z) * size_t(rs.y) + size_t(y - region.lo.y)) * stride;
        for (int x = lo.x; x < hi.x; ++x) {
          const float dx = float(x) - q.x;
          uint32_t& held = row[size_t(x - region.lo.x)];
          held = std::min(held, make_key(scaled_base + dx * dx * scale, limit, uint32_t(id) + 1));
        }
      }
  }
}

}  // namespace

uint32_t unreached_key(int reach) {
  const float reach2 = float(reach * reach);
  const float scale = distance_scale(reach2), limit = reach2 * scale;
  return make_key(limit, limit, 0);
}

void offer_seeds(std::span<const glm::vec3> points, const Box& region, const Box& clip,
                 size_t stride, int reach, uint32_t* keys) {
  if (2 * reach > kLaneCount) {
    offer_wide(points, region, clip, stride, reach, keys);
    return;
  }
  static const auto kernel = __builtin_cpu_supports("avx512f") ? offer_avx512
                             : __builtin_cpu_supports("avx2")  ? offer_avx2
                                                               : offer_baseline;
  kernel(points, region, clip, stride, reach, keys);
}

}  // namespace sculpt::core
