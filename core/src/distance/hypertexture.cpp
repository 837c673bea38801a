#include "sculpt/core/distance/hypertexture.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "sculpt/core/distance/iso_triangulation.h"
#include "sculpt/core/distance/morphology.h"
#include "sculpt/core/util/parallel_for.h"

namespace sculpt::core {
namespace {

uint32_t hash(int x, int y, int z, uint32_t seed) {
  uint32_t h = seed * 0x9E3779B9u;
  h ^= uint32_t(x) * 0x85EBCA6Bu;
  h = (h ^ (h >> 13)) * 0xC2B2AE35u;
  h ^= uint32_t(y) * 0x27D4EB2Fu;
  h = (h ^ (h >> 15)) * 0x165667B1u;
  h ^= uint32_t(z) * 0x9E3779B1u;
  return (h ^ (h >> 16)) * 0x85EBCA77u;
}

// Perlin's gradient noise: 12 edge-direction gradients, quintic fade.
float gradient_noise(glm::vec3 p, uint32_t seed) {
  static constexpr float kGrad[12][3] = {{1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0},
                                         {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
                                         {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}};
  const glm::vec3 f = glm::floor(p);
  const glm::ivec3 i(f);
  const glm::vec3 t = p - f;
  const glm::vec3 u = t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
  float c[8];
  for (int k = 0; k < 8; ++k) {
    const glm::ivec3 o(k & 1, (k >> 1) & 1, k >> 2);
    const float* g = kGrad[hash(i.x + o.x, i.y + o.y, i.z + o.z, seed) % 12];
    const glm::vec3 d = t - glm::vec3(o);
    c[k] = g[0] * d.x + g[1] * d.y + g[2] * d.z;
  }
  const float x00 = glm::mix(c[0], c[1], u.x), x10 = glm::mix(c[2], c[3], u.x);
  const float x01 = glm::mix(c[4], c[5], u.x), x11 = glm::mix(c[6], c[7], u.x);
  return glm::mix(glm::mix(x00, x10, u.y), glm::mix(x01, x11, u.y), u.z);
}

uint8_t skin_density(float d, glm::vec3 p, uint8_t old, const HypertextureOptions& o) {
  if (d <= 0.0f || d > o.width_vox) return old;
  const float pushed = d - o.amplitude * o.width_vox * hypertexture_turbulence(p, o);
  const float f = std::clamp(1.0f - pushed / o.width_vox, 0.0f, 1.0f);
  return std::max(old, uint8_t(std::min(255.0f, 255.0f * f * f)));
}

}  // namespace

float hypertexture_turbulence(glm::vec3 p, const HypertextureOptions& o) {
  float sum = 0.0f, norm = 0.0f, amp = 1.0f, freq = o.frequency;
  for (int k = 0; k < std::max(1, o.octaves); ++k) {
    sum += amp * std::abs(gradient_noise(p * freq, o.seed + uint32_t(k)));
    norm += amp;
    amp *= 0.5f;
    freq *= 2.0f;
  }
  // |gradient noise| stays below about 1; normalise the octave sum to [0, 1).
  return std::min(sum / norm, 0.999f);
}

int64_t bake_hypertexture(DenseGrid<uint8_t>& density, const Box& box,
                          const HypertextureOptions& o) {
  const DenseGrid<float> dist = surface_distance(level_function(density), o.threads);
  const Box b = intersect(box, Box{glm::ivec3(0), density.dims()});
  int64_t changed = 0;
  for (int z = b.lo.z; z < b.hi.z; ++z)
    for (int y = b.lo.y; y < b.hi.y; ++y)
      for (int x = b.lo.x; x < b.hi.x; ++x) {
        uint8_t& v = density.at(x, y, z);
        const uint8_t n = skin_density(dist.at(x, y, z), glm::vec3(x, y, z), v, o);
        changed += n != v;
        v = n;
      }
  return changed;
}

int64_t bake_hypertexture(Volume& volume, const Box& box, const HypertextureOptions& o) {
  const Box target = intersect(box, Box{glm::ivec3(0), volume.dims()});
  if (target.empty()) return 0;
  const int margin = int(std::ceil(o.width_vox)) + 2;
  const Box region{target.lo - margin, target.hi + margin};
  DenseGrid<uint8_t> local = volume.read(region);
  const Box inner{target.lo - region.lo, target.hi - region.lo};
  // Noise in volume coordinates, so neighbouring brush boxes join seamlessly.
  const DenseGrid<float> dist = surface_distance(level_function(local), o.threads);
  DenseGrid<uint8_t> out(target.size());
  int64_t changed = 0;
  for (int z = 0; z < out.dims().z; ++z)
    for (int y = 0; y < out.dims().y; ++y)
      for (int x = 0; x < out.dims().x; ++x) {
        const glm::ivec3 l = inner.lo + glm::ivec3(x, y, z);
        const uint8_t old = local.at(l.x, l.y, l.z);
        const uint8_t n = skin_density(dist.at(l.x, l.y, l.z),
                                       glm::vec3(target.lo + glm::ivec3(x, y, z)), old, o);
        changed += n != old;
        out.at(x, y, z) = n;
      }
  if (changed > 0) volume.write(target.lo, out);
  return changed;
}

}  // namespace sculpt::core
