#include "nearest_seed.h"

#include <algorithm>
#include <cstring>

#include <glm/common.hpp>

namespace sculpt::core {
namespace {

constexpr uint32_t kNumberMask = uint32_t(kMaxSeeds);

// The fixed-point scale of a key's distance part: reach^2 maps to 16383
// above the number's 16 bits, so a row's sum of two parts each kept below
// that stays below 2^31 (the conversion is signed).
float distance_scale(float reach2) {
  return 16383.0f * 65536.0f / reach2;
}

inline uint32_t make_key(float scaled_d2, float limit, uint32_t number) {
  return (uint32_t(int32_t(std::min(scaled_d2, limit))) & ~kNumberMask) | number;
}

// Sixteen values of a row, as one, two or four vectors.
using Floats16 = float __attribute__((vector_size(64)));
using Keys16 = uint32_t __attribute__((vector_size(64)));
using Ints16 = int32_t __attribute__((vector_size(64)));
using Floats8 = float __attribute__((vector_size(32)));
using Keys8 = uint32_t __attribute__((vector_size(32)));
using Ints8 = int32_t __attribute__((vector_size(32)));
using Floats4 = float __attribute__((vector_size(16)));
using Keys4 = uint32_t __attribute__((vector_size(16)));
using Ints4 = int32_t __attribute__((vector_size(16)));
constexpr int kLaneCount = 16;

// A row of a seed's ball spans at most 2 * reach <= 16 values: sixteen lanes
// from its left end (one AVX-512 vector, two of AVX2, four of SSE2: GCC
// splits a generic vector wider than the target's badly). Per seed, the lanes' squared x distances
// are kept below the key's limit, so a row's sum stays below 2^31 and
// converts exactly; lanes out of reach make a distance above the unreached
// key's, so never win.
template <class Floats, class Keys, class Ints>
inline __attribute__((always_inline)) void offer_body(std::span<const glm::vec3> points,
                                                      const Box& region, const Box& clip,
                                                      size_t stride, int reach, uint32_t* keys) {
  constexpr int kLanes = int(sizeof(Floats) / sizeof(float));
  constexpr int kSteps = kLaneCount / kLanes;
  const glm::ivec3 rs = region.size();
  const float reach2 = float(reach * reach);
  const float scale = distance_scale(reach2), limit = reach2 * scale;
  const size_t plane = size_t(rs.y) * stride;
  Floats lanes;
  for (int i = 0; i < kLanes; ++i)
    lanes[i] = float(i);
  for (size_t id = 0; id < points.size(); ++id) {
    const glm::vec3 q = points[id];
    const glm::ivec3 centre = glm::ivec3(glm::floor(q));
    const glm::ivec3 lo = glm::max(centre - reach + 1, clip.lo);
    const glm::ivec3 hi = glm::min(centre + reach + 1, clip.hi);
    if (hi.x <= lo.x || hi.y <= lo.y || hi.z <= lo.z) continue;
    Floats dx2[kSteps];
    for (int s = 0; s < kSteps; ++s) {
      const Floats dx = (float(lo.x + s * kLanes) - q.x) + lanes;
      const Floats scaled = dx * dx * scale;
      dx2[s] = scaled < limit ? scaled : Floats{} + limit;
    }
    const uint32_t number = uint32_t(id) + 1;
    uint32_t* slab = keys + size_t(lo.z - region.lo.z) * plane +
                     size_t(lo.y - region.lo.y) * stride + size_t(lo.x - region.lo.x);
    float dz = float(lo.z) - q.z;
    for (int z = lo.z; z < hi.z; ++z, dz += 1.0f, slab += plane) {
      const float dz2 = dz * dz;
      uint32_t* row = slab;
      float dy = float(lo.y) - q.y;
      for (int y = lo.y; y < hi.y; ++y, dy += 1.0f, row += stride) {
        const float base = dz2 + dy * dy;
        if (base >= reach2) continue;
        const float scaled_base = base * scale;
        for (int s = 0; s < kSteps; ++s) {
          const Floats d2 = scaled_base + dx2[s];
          Keys k = (Keys) __builtin_convertvector(d2, Ints);
          k = (k & ~kNumberMask) | number;
          Keys held;
          std::memcpy(&held, row + s * kLanes, sizeof held);
          held = k < held ? k : held;
          std::memcpy(row + s * kLanes, &held, sizeof held);
        }
      }
    }
  }
}

// Dispatched by hand rather than with target_clones: an ifunc resolver runs
// before ThreadSanitizer's runtime is up and crashes the instrumented build.
__attribute__((target("avx512f"))) void offer_avx512(std::span<const glm::vec3> points,
                                                     const Box& region, const Box& clip,
                                                     size_t stride, int reach, uint32_t* keys) {
  offer_body<Floats16, Keys16, Ints16>(points, region, clip, stride, reach, keys);
}

__attribute__((target("avx2"))) void offer_avx2(std::span<const glm::vec3> points,
                                                const Box& region, const Box& clip, size_t stride,
                                                int reach, uint32_t* keys) {
  offer_body<Floats8, Keys8, Ints8>(points, region, clip, stride, reach, keys);
}

void offer_baseline(std::span<const glm::vec3> points, const Box& region, const Box& clip,
                    size_t stride, int reach, uint32_t* keys) {
  offer_body<Floats4, Keys4, Ints4>(points, region, clip, stride, reach, keys);
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
