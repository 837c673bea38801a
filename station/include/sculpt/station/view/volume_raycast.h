#pragma once
// Where a ray from the camera first meets the material: how the ordinary
// mouse places the tool on the surface under the cursor. GL-free.

#include <optional>

#include "sculpt/core/volume/volume.h"
#include "sculpt/station/view/orbit_camera.h"

namespace sculpt::station {

/// The first point along `ray` inside the block whose density exceeds `iso`,
/// to a tenth of a voxel; nullopt when the ray misses the material. Cost:
/// O(length of the ray inside the block x levels).
std::optional<glm::vec3> raycast_surface(const core::Volume& volume, const Ray& ray,
                                         float iso = 127.5f);

}  // namespace sculpt::station
