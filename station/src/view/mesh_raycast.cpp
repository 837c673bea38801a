#include "sculpt/station/view/mesh_raycast.h"

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

namespace sculpt::station {

std::optional<glm::vec3> raycast_mesh(const core::Mesh& mesh, const Ray& ray) {
  // Möller & Trumbore, "Fast, minimum storage ray/triangle intersection"
  // (1997): barycentric (u, v) and distance t from one 3x3 solve.
  constexpr float kParallel = 1e-12f;
  float best = std::numeric_limits<float>::infinity();
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::vec3 a = mesh.positions[t.x];
    const glm::vec3 e1 = mesh.positions[t.y] - a, e2 = mesh.positions[t.z] - a;
    const glm::vec3 p = glm::cross(ray.direction, e2);
    const float det = glm::dot(e1, p);
    if (std::abs(det) < kParallel) continue;
    const float inv = 1.0f / det;
    const glm::vec3 s = ray.origin - a;
    const float u = glm::dot(s, p) * inv;
    if (u < 0.0f || u > 1.0f) continue;
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(ray.direction, q) * inv;
    if (v < 0.0f || u + v > 1.0f) continue;
    const float dist = glm::dot(e2, q) * inv;
    if (dist > 0.0f && dist < best) best = dist;
  }
  if (!std::isfinite(best)) return std::nullopt;
  return ray.origin + best * ray.direction;
}

std::optional<glm::vec3> raycast_plane(const Ray& ray, glm::vec3 point, glm::vec3 normal) {
  const float along = glm::dot(ray.direction, normal);
  if (std::abs(along) < 1e-6f) return std::nullopt;
  const float t = glm::dot(point - ray.origin, normal) / along;
  if (!(t > 0.0f)) return std::nullopt;
  return ray.origin + t * ray.direction;
}

}  // namespace sculpt::station
