// The panel drawn from its layer (window/panel_layer.h) must look as the
// panel drawn directly does, over any picture, and be drawn anew exactly
// when it changes. Without a display the test runs itself again under
// xvfb-run (Mesa's software OpenGL, as in CI).

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "imgui_gl_window.h"
#include "scratch_dir.h"
#include "sculpt/station/window/gl_snapshot.h"
#include "sculpt/station/window/panel_layer.h"
#include "xvfb_rerun.h"

namespace sculpt::station {
namespace {

constexpr int kWidth = 320, kHeight = 240;

// A panel like the station's: a translucent window with text and a button.
ImDrawData& panel_frame(const std::string& line) {
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(kWidth, kHeight);
  io.DeltaTime = 1.0f / 60.0f;
  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();
  ImGui::SetNextWindowPos(ImVec2(20, 30));
  ImGui::SetNextWindowSize(ImVec2(200, 120));
  ImGui::SetNextWindowBgAlpha(0.6f);
  ImGui::Begin("Sculpt station");
  ImGui::TextUnformatted(line.c_str());
  ImGui::Button("Frame the sculpture");
  ImGui::End();
  ImGui::Render();
  return *ImGui::GetDrawData();
}

// Quadrants of four colours under the panel: its blending shows on each.
void draw_background() {
  glViewport(0, 0, kWidth, kHeight);
  glEnable(GL_SCISSOR_TEST);
  const float colours[4][3] = {
      {0.9f, 0.2f, 0.1f}, {0.1f, 0.7f, 0.3f}, {0.2f, 0.3f, 0.9f}, {0.95f, 0.95f, 0.9f}};
  for (int q = 0; q < 4; ++q) {
    glScissor((q % 2) * kWidth / 2, (q / 2) * kHeight / 2, kWidth / 2, kHeight / 2);
    glClearColor(colours[q][0], colours[q][1], colours[q][2], 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
  }
  glDisable(GL_SCISSOR_TEST);
}

std::vector<uint8_t> pixels() {
  std::vector<uint8_t> rgb(static_cast<size_t>(kWidth) * kHeight * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, kWidth, kHeight, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  return rgb;
}

struct Compared {
  int worst = 0;          // largest channel difference
  int64_t different = 0;  // pixels that differ at all
};

Compared compare(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  Compared c;
  for (size_t i = 0; i < a.size(); i += 3) {
    int worst = 0;
    for (size_t k = 0; k < 3; ++k)
      worst = std::max(worst, std::abs(int{a[i + k]} - int{b[i + k]}));
    c.worst = std::max(c.worst, worst);
    c.different += worst > 0;
  }
  return c;
}

std::vector<uint8_t> drawn_directly(const std::string& line) {
  draw_background();
  ImGui_ImplOpenGL3_RenderDrawData(&panel_frame(line));
  return pixels();
}

std::vector<uint8_t> drawn_through(PanelLayer& layer, const std::string& line,
                                   uint64_t textures_version = 0) {
  draw_background();
  layer.draw(panel_frame(line), textures_version);
  return pixels();
}

TEST(PanelLayer, LooksAsThePanelDrawnDirectlyAndIsDrawnAnewOnlyWhenItChanges) {
  if (!display_available()) {
    sculpt::test::ScratchDir dir;
    if (!sculpt::test::rerun_under_xvfb(dir)) GTEST_SKIP() << "no display and no xvfb-run";
    return;
  }
  test::ImGuiGlWindow gl(kWidth, kHeight, "panel layer test");
  ASSERT_NE(gl.get(), nullptr) << "no OpenGL 3.3 context";
  draw_background();
  const std::vector<uint8_t> background = pixels();

  // ImGui settles a new window over its first frames (its size, its focus).
  for (int i = 0; i < 3; ++i)
    panel_frame("60 fps (16.7 ms)");
  const std::vector<uint8_t> direct = drawn_directly("60 fps (16.7 ms)");
  ASSERT_EQ(compare(drawn_directly("60 fps (16.7 ms)"), direct).different, 0) << "settled";
  ASSERT_GT(compare(direct, background).different, 5000) << "the panel shows";
  // The first frame through the layer: drawn into it, then shown.
  PanelLayer layer;
  const std::vector<uint8_t> first = drawn_through(layer, "60 fps (16.7 ms)");
  EXPECT_EQ(layer.frames(), 1);
  EXPECT_EQ(layer.rasters(), 1);
  // Premultiplied in 8 bits, then blended: a step of at most 2 of 255.
  EXPECT_LE(compare(first, direct).worst, 2);

  // The same panel again: from the layer, the same pixels.
  const std::vector<uint8_t> again = drawn_through(layer, "60 fps (16.7 ms)");
  EXPECT_EQ(layer.frames(), 2);
  EXPECT_EQ(layer.rasters(), 1);
  EXPECT_EQ(compare(again, first).different, 0);

  // A changed figure: drawn anew, and it shows.
  const std::vector<uint8_t> changed = drawn_through(layer, "58 fps (17.2 ms)");
  EXPECT_EQ(layer.rasters(), 2);
  EXPECT_GT(compare(changed, first).different, 0);
  EXPECT_LE(compare(changed, drawn_directly("58 fps (17.2 ms)")).worst, 2);

  // The same draw data over new textures: drawn anew.
  drawn_through(layer, "58 fps (17.2 ms)", /*textures_version=*/1);
  EXPECT_EQ(layer.rasters(), 3);
  drawn_through(layer, "58 fps (17.2 ms)", /*textures_version=*/1);
  EXPECT_EQ(layer.rasters(), 3);
}

}  // namespace
}  // namespace sculpt::station
