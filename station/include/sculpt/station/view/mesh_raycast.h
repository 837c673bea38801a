#pragma once
// Where a ray from the camera meets a triangle mesh or a plane: how the
// ordinary mouse puts the tool on the NURBS sheet under the cursor, and drags
// it at a constant depth. GL-free.

#include <optional>

#include "sculpt/core/mesh/mesh.h"
#include "sculpt/station/view/orbit_camera.h"

namespace sculpt::station {

/// The nearest point where `ray` crosses a triangle of `mesh` (either side;
/// Möller-Trumbore), nullopt when it misses them all. O(triangles).
std::optional<glm::vec3> raycast_mesh(const core::Mesh& mesh, const Ray& ray);

/// Where `ray` crosses the plane through `point` with normal `normal`
/// (ahead of the ray's origin), nullopt when parallel to it or behind.
std::optional<glm::vec3> raycast_plane(const Ray& ray, glm::vec3 point, glm::vec3 normal);

}  // namespace sculpt::station
