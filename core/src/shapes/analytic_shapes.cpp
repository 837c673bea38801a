#include "sculpt/core/shapes/analytic_shapes.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace sculpt::core {

uint8_t density_from_distance(float d) {
  // float32 throughout, as numpy computes it in peers.py, so both build the
  // same bytes.
  const float v = std::clamp(127.5f - d * 127.5f, 0.0f, 255.0f);
  return static_cast<uint8_t>(v);
}

void fill_sphere(const Box& box, glm::vec3 centre, float radius, std::span<uint8_t> out) {
  size_t i = 0;
  for (int z = box.lo.z; z < box.hi.z; ++z) {
    const float dz = static_cast<float>(z) - centre.z;
    for (int y = box.lo.y; y < box.hi.y; ++y) {
      const float dy = static_cast<float>(y) - centre.y;
      for (int x = box.lo.x; x < box.hi.x; ++x) {
        const float dx = static_cast<float>(x) - centre.x;
        out[i++] = density_from_distance(std::sqrt(dx * dx + dy * dy + dz * dz) - radius);
      }
    }
  }
}

DenseGrid<uint8_t> sphere_density(int n, float r_frac) {
  DenseGrid<uint8_t> grid{glm::ivec3(n)};
  const float c = static_cast<float>(n - 1) / 2.0f;
  fill_sphere(Box{glm::ivec3(0), glm::ivec3(n)}, glm::vec3(c), r_frac * static_cast<float>(n),
              grid.values());
  return grid;
}

Volume sphere_volume(int n, float r_frac, const VolumeOptions& options) {
  const float c = static_cast<float>(n - 1) / 2.0f;
  const float r = r_frac * static_cast<float>(n);
  return Volume::from_bricks(glm::ivec3(n), options, [&](const Box& box, std::span<uint8_t> out) {
    fill_sphere(box, glm::vec3(c), r, out);
  });
}

namespace {

template <class SignedDistance>
DenseGrid<uint8_t> from_distance(glm::ivec3 dims, SignedDistance sd) {
  DenseGrid<uint8_t> grid(dims);
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x)
        grid.at(x, y, z) = density_from_distance(sd(glm::vec3(x, y, z)));
  return grid;
}

}  // namespace

DenseGrid<uint8_t> torus_density(glm::ivec3 dims, glm::vec3 centre, float major_radius,
                                 float minor_radius) {
  return from_distance(dims, [=](glm::vec3 p) {
    const glm::vec3 q = p - centre;
    const float ring = std::sqrt(q.x * q.x + q.y * q.y) - major_radius;
    return std::sqrt(ring * ring + q.z * q.z) - minor_radius;
  });
}

DenseGrid<uint8_t> box_density(glm::ivec3 dims, glm::vec3 lo, glm::vec3 hi) {
  const glm::vec3 centre = (lo + hi) * 0.5f;
  const glm::vec3 half = (hi - lo) * 0.5f;
  return from_distance(dims, [=](glm::vec3 p) {
    const glm::vec3 q = glm::abs(p - centre) - half;
    const float outside = glm::length(glm::max(q, glm::vec3(0.0f)));
    const float inside = std::min(std::max(q.x, std::max(q.y, q.z)), 0.0f);
    return outside + inside;
  });
}

}  // namespace sculpt::core
