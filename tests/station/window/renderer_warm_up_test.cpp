// The renderer's warm-up (SceneRenderer::warm_up: every state drawn once, so
// that a software renderer's code for it is made before the sculptor's first
// dab) must leave the renderer as it found it: the clay, the stand-ins and
// the tool drawn after it are the same pixels as without it. Without a
// display the test runs itself again under xvfb-run (Mesa's software
// OpenGL, as in CI).

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "render/gl/scene_renderer.h"
#include "scratch_dir.h"
#include "sculpt/core/tool/tool.h"
#include "sculpt/station/view/orbit_camera.h"
#include "sculpt/station/view/tool_outline.h"
#include "sculpt/station/window/gl_snapshot.h"
#include "window/gl_context.h"
#include "xvfb_rerun.h"

namespace sculpt::station {
namespace {

constexpr int kPixels = 200;
constexpr float kBlock = 64.0f;

// The renderer's picture of a ball of clay with a tool and two stand-ins
// (one adding, one carving) over it, drawn into an off-screen framebuffer;
// `warm` warms the renderer up after it was given them, and again before.
std::vector<uint8_t> picture(bool warm) {
  auto window = GlWindow::open(64, 64, "warm-up test", /*visible=*/false);
  EXPECT_TRUE(window.ok());
  if (!window) return {};
  auto renderer = gl::SceneRenderer::create();
  EXPECT_TRUE(renderer.ok());
  if (!renderer) return {};
  const OffscreenTarget target(kPixels, kPixels);
  EXPECT_TRUE(target.complete());

  if (warm) (*renderer)->warm_up(kPixels, kPixels);
  // The clay: a ball of radius 20 in the block's middle.
  const core::Tool ball = core::make_sphere_tool(20.0f);
  core::Mesh clay = window_tool_outline(ball);
  for (glm::vec3& p : clay.positions)
    p += glm::vec3(kBlock / 2) - ball.pivot;
  (*renderer)->show_mesh(clay);
  const core::Tool tool = core::make_sphere_tool(8.0f);
  (*renderer)->set_tool(tool, 1);
  (*renderer)->set_stand_in_tool(DabStandIns::ToolMesh::of(tool, 1));
  std::vector<DabStandIn> stand_ins(2);
  stand_ins[0].position = {32.0f, 50.0f, 40.0f};
  stand_ins[0].tool_version = 1;
  stand_ins[1].position = {40.0f, 32.0f, 50.0f};
  stand_ins[1].tool_version = 1;
  stand_ins[1].carves = true;
  if (warm) (*renderer)->warm_up(kPixels, kPixels);

  OrbitCamera camera;
  camera.frame(glm::vec3(0.0f), glm::vec3(kBlock));
  const gl::SceneView view{camera.view(), camera.projection(1.0f), camera.eye(), kPixels, kPixels};
  gl::ToolDraw pointer;
  pointer.position = {20.0f, 40.0f, 52.0f};
  pointer.pressed = true;
  (*renderer)->draw(view, pointer, glm::vec3(kBlock), stand_ins);
  glFinish();
  std::vector<uint8_t> rgb;
  read_pixels(kPixels, kPixels, rgb);
  return rgb;
}

TEST(RendererWarmUp, LeavesThePictureAsItWas) {
  if (!display_available()) {
    sculpt::test::ScratchDir dir;
    if (!sculpt::test::rerun_under_xvfb(dir)) GTEST_SKIP() << "no display and no xvfb-run";
    return;
  }
  const std::vector<uint8_t> cold = picture(false);
  const std::vector<uint8_t> warmed = picture(true);
  ASSERT_EQ(cold.size(), static_cast<size_t>(kPixels * kPixels * 3));
  // The picture shows something: clay, tool and stand-ins over the background.
  int64_t lit = 0;
  for (size_t i = 0; i + 2 < cold.size(); i += 3)
    lit += cold[i] != cold[0] || cold[i + 1] != cold[1] || cold[i + 2] != cold[2];
  EXPECT_GT(lit, kPixels * kPixels / 20);
  int64_t differing = 0;
  for (size_t i = 0; i < cold.size(); ++i)
    differing += cold[i] != warmed[i];
  EXPECT_EQ(differing, 0);
}

}  // namespace
}  // namespace sculpt::station
