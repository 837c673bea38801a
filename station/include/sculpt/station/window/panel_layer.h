#pragma once
// The panel's pixels, kept between the frames that do not change them.
//
// Mesa's software OpenGL spends about 5 ms of a 1280x800 frame blending the
// panel's few thousand triangles, although the panel looks the same in most
// frames: the sculptor moves the tool, not the panel. The layer keeps the
// panel's picture in a texture and draws it with one blended rectangle; it
// draws the panel into the texture again only when ImGui's draw data differ
// from the last ones it drew (compared byte for byte: a hover, a click, a
// moved window, a changed figure) or when the caller says the textures the
// panel shows have changed. The picture is the panel's own, kept with
// premultiplied alpha, so compositing it equals drawing the panel (to 8-bit
// rounding).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

struct ImDrawData;

namespace sculpt::station {

class PanelLayer {
 public:
  PanelLayer();
  /// Frees the GL objects: the context that drew must still be current.
  ~PanelLayer();
  PanelLayer(const PanelLayer&) = delete;
  PanelLayer& operator=(const PanelLayer&) = delete;

  /// Draws `panel` over the bound framebuffer. `textures_version` is any
  /// number that changes when the contents of a texture the panel shows do
  /// (thumbnails uploaded again under the same names).
  void draw(ImDrawData& panel, uint64_t textures_version);

  /// Frames drawn, and how many of them drew the panel's triangles.
  int64_t frames() const { return frames_; }
  int64_t rasters() const { return rasters_; }

 private:
  struct Gl;
  // The draw data's bytes that decide what is drawn, in `out`.
  static void describe(const ImDrawData& panel, uint64_t textures_version,
                       std::vector<std::byte>& out);

  std::unique_ptr<Gl> gl_;
  std::vector<std::byte> drawn_;  // describe() of the picture in the layer
  std::vector<std::byte> next_;
  int64_t frames_ = 0;
  int64_t rasters_ = 0;
};

}  // namespace sculpt::station
