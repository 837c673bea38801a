#include "sculpt/station/render/software_renderer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sculpt/core/mesh/mesh_cache.h"
#include "sculpt/core/shapes/analytic_shapes.h"

namespace sculpt::station {
namespace {

core::Mesh sphere_mesh() {
  const core::Volume v = core::sphere_volume(64);
  core::MeshCache cache(0);
  cache.update(v);
  return cache.welded_mesh();
}

TEST(SoftwareRenderer, SphereSilhouetteCoversItsDisc) {
  const core::Mesh mesh = sphere_mesh();
  const SoftwareView view = view_of(mesh, glm::vec3(0), glm::vec3(64));
  const RgbImage img = render_mesh(mesh, view);
  ASSERT_EQ(img.rgb.size(), static_cast<size_t>(view.width) * view.height * 3);
  // The view frames the sphere's bounding box: the picture spans the box's
  // diagonal (sqrt 3 times the diameter) over 95% of the width, so the disc
  // covers pi/4 * (0.95 / sqrt 3)^2 of the picture.
  const double expected = 3.14159265 / 4 * std::pow(0.95 / std::sqrt(3.0), 2);
  EXPECT_NEAR(coverage(img, view), expected, 0.02);
}

TEST(SoftwareRenderer, LightsTheSideFacingTheKeyLight) {
  const core::Mesh mesh = sphere_mesh();
  SoftwareView view = view_of(mesh, glm::vec3(0), glm::vec3(64));
  view.toward_camera = glm::vec3(0, 0, 1);
  const RgbImage img = render_mesh(mesh, view);
  auto brightness = [&](int x, int y) {
    const size_t i = (static_cast<size_t>(y) * img.width + x) * 3;
    return img.rgb[i] + img.rgb[i + 1] + img.rgb[i + 2];
  };
  const int c = img.width / 2, d = img.width / 8;
  EXPECT_GT(brightness(c - d, c - d), brightness(c + d, c + d));  // key light: upper left
}

TEST(SoftwareRenderer, EmptyMeshIsJustTheBackground) {
  const SoftwareView view = view_of(core::Mesh{}, glm::vec3(0), glm::vec3(10));
  EXPECT_EQ(coverage(render_mesh(core::Mesh{}, view), view), 0.0);
}

}  // namespace
}  // namespace sculpt::station
