#pragma once
// A CPU rasteriser for pictures without a display: `sculpt replay --png` and
// the headless main job. Orthographic view of a box (the block of material)
// from a chosen direction, z-buffered triangles with smooth vertex normals,
// a key light, a fill light and ambient, over a studio gradient. The window
// (GL) renderer draws the same scene interactively; this one needs no GPU.

#include <cstdint>
#include <filesystem>
#include <vector>

#include <glm/vec3.hpp>

#include "sculpt/base/result.h"
#include "sculpt/core/mesh/mesh.h"

namespace sculpt::station {

struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgb;  ///< width * height * 3, rows top to bottom
};

struct SoftwareView {
  /// The box framed by the picture, voxel units.
  glm::vec3 box_lo{0.0f};
  glm::vec3 box_hi{256.0f};
  /// Direction from the box's centre toward the camera (need not be unit).
  glm::vec3 toward_camera{0.45f, 0.35f, 1.0f};
  int width = 800;
  int height = 800;
};

/// A view framing the mesh's bounding box (or `box_lo`..`box_hi` when the
/// mesh is empty).
SoftwareView view_of(const core::Mesh& mesh, glm::vec3 box_lo, glm::vec3 box_hi);

/// Renders `mesh` (normals used when present, else face normals).
RgbImage render_mesh(const core::Mesh& mesh, const SoftwareView& view);
/// Fraction of pixels the mesh covers (not background): the silhouette's share.
double coverage(const RgbImage& image, const SoftwareView& view);

/// Writes a PNG, all or nothing.
Status write_png(const std::filesystem::path& path, const RgbImage& image);

}  // namespace sculpt::station
