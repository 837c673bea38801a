#include "sculpt/station/window/panel_layer.h"

#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>

#include "render/gl/gl_api.h"
#include "render/gl/shader_program.h"

namespace sculpt::station {
namespace {

// One rectangle (u_rect: its corners in clip space) showing the layer's
// texels one to one; the layer is the framebuffer's size.
constexpr const char* kCompositeVertex = R"(#version 330 core
uniform vec4 u_rect;
void main() {
  vec2 corner = vec2(gl_VertexID & 1, gl_VertexID >> 1);
  gl_Position = vec4(mix(u_rect.xy, u_rect.zw, corner), 0.0, 1.0);
}
)";
constexpr const char* kCompositeFragment = R"(#version 330 core
uniform sampler2D u_layer;
out vec4 colour;
void main() { colour = texelFetch(u_layer, ivec2(gl_FragCoord.xy), 0); }
)";

// Resized, then copied: GCC 12 warns falsely about vector::insert here.
void append_bytes(std::vector<std::byte>& out, const void* bytes, size_t n) {
  const size_t at = out.size();
  out.resize(at + n);
  if (n > 0) std::memcpy(out.data() + at, bytes, n);
}

template <class T>
void append(std::vector<std::byte>& out, const T& value) {
  append_bytes(out, &value, sizeof(T));
}

template <class T>
void append_all(std::vector<std::byte>& out, const ImVector<T>& values) {
  append(out, values.Size);
  append_bytes(out, values.Data, sizeof(T) * static_cast<size_t>(values.Size));
}

// The pixels the panel's triangles can touch, in framebuffer pixels with
// y up (as OpenGL counts them): x0, y0, x1, y1.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
};

PixelRect covered(const ImDrawData& d, int width, int height) {
  float lo_x = INFINITY, lo_y = INFINITY, hi_x = -INFINITY, hi_y = -INFINITY;
  for (int l = 0; l < d.CmdListsCount; ++l) {
    for (const ImDrawVert& v : d.CmdLists[l]->VtxBuffer) {
      lo_x = std::min(lo_x, v.pos.x);
      lo_y = std::min(lo_y, v.pos.y);
      hi_x = std::max(hi_x, v.pos.x);
      hi_y = std::max(hi_y, v.pos.y);
    }
  }
  if (lo_x > hi_x) return {};
  const float sx = d.FramebufferScale.x, sy = d.FramebufferScale.y;
  // One pixel more each way: antialiased edges reach past their vertices.
  const int x0 = static_cast<int>(std::floor((lo_x - d.DisplayPos.x) * sx)) - 1;
  const int x1 = static_cast<int>(std::ceil((hi_x - d.DisplayPos.x) * sx)) + 1;
  const int top = static_cast<int>(std::floor((lo_y - d.DisplayPos.y) * sy)) - 1;
  const int bottom = static_cast<int>(std::ceil((hi_y - d.DisplayPos.y) * sy)) + 1;
  PixelRect r;
  r.x0 = std::clamp(x0, 0, width);
  r.x1 = std::clamp(x1, 0, width);
  r.y0 = std::clamp(height - bottom, 0, height);
  r.y1 = std::clamp(height - top, 0, height);
  return r;
}

}  // namespace

struct PanelLayer::Gl {
  std::optional<gl::ShaderProgram> composite;  // empty: drawing directly
  bool failed = false;                         // no layer on this driver
  GLuint framebuffer = 0;
  GLuint texture = 0;
  GLuint empty_vao = 0;  // the core profile draws nothing without one
  int width = 0, height = 0;
  PixelRect rect;

  ~Gl() {
    if (texture != 0) glDeleteTextures(1, &texture);
    if (framebuffer != 0) glDeleteFramebuffers(1, &framebuffer);
    if (empty_vao != 0) glDeleteVertexArrays(1, &empty_vao);
  }

  bool make(int w, int h) {
    if (failed) return false;
    if (!composite) {
      Result<gl::ShaderProgram> p =
          gl::ShaderProgram::build(kCompositeVertex, kCompositeFragment, "panel layer");
      if (!p) return failed = true, false;
      composite.emplace(std::move(*p));
      glGenVertexArrays(1, &empty_vao);
      glGenFramebuffers(1, &framebuffer);
      glGenTextures(1, &texture);
    }
    if (w == width && h == height) return true;
    GLint bound_texture = 0, bound_framebuffer = 0;
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound_texture);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound_framebuffer);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
    glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, 0);
    const bool complete = glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(bound_framebuffer));
    glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(bound_texture));
    if (!complete) return failed = true, false;
    width = w;
    height = h;
    return true;
  }

  // The panel's triangles into the layer. ImGui blends colour by source
  // alpha and alpha by one: over a transparent layer that leaves the
  // panel's colour premultiplied by its coverage, and its coverage.
  void raster(ImDrawData& panel) {
    GLint bound_framebuffer = 0;
    GLfloat clear[4];
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound_framebuffer);
    glGetFloatv(GL_COLOR_CLEAR_VALUE, clear);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
    glClearColor(0, 0, 0, 0);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(&panel);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(bound_framebuffer));
    glClearColor(clear[0], clear[1], clear[2], clear[3]);
    rect = covered(panel, width, height);
  }

  // The layer over the bound framebuffer: premultiplied "over".
  void show() const {
    if (rect.empty()) return;
    GLint program = 0, vao = 0, texture_unit = 0, bound_texture = 0;
    GLint blend_src_rgb = 0, blend_dst_rgb = 0, blend_src_alpha = 0, blend_dst_alpha = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &program);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &texture_unit);
    glActiveTexture(GL_TEXTURE0);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound_texture);
    glGetIntegerv(GL_BLEND_SRC_RGB, &blend_src_rgb);
    glGetIntegerv(GL_BLEND_DST_RGB, &blend_dst_rgb);
    glGetIntegerv(GL_BLEND_SRC_ALPHA, &blend_src_alpha);
    glGetIntegerv(GL_BLEND_DST_ALPHA, &blend_dst_alpha);
    const GLboolean blend = glIsEnabled(GL_BLEND), depth = glIsEnabled(GL_DEPTH_TEST),
                    cull = glIsEnabled(GL_CULL_FACE), scissor = glIsEnabled(GL_SCISSOR_TEST),
                    stencil = glIsEnabled(GL_STENCIL_TEST);
    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);

    glViewport(0, 0, width, height);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    composite->use();
    auto clip = [](int pixel, int size) {
      return 2.0f * static_cast<float>(pixel) / static_cast<float>(size) - 1.0f;
    };
    composite->set("u_rect", glm::vec4(clip(rect.x0, width), clip(rect.y0, height),
                                       clip(rect.x1, width), clip(rect.y1, height)));
    glBindTexture(GL_TEXTURE_2D, texture);
    glBindVertexArray(empty_vao);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);

    glBindVertexArray(static_cast<GLuint>(vao));
    glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(bound_texture));
    glActiveTexture(static_cast<GLenum>(texture_unit));
    glUseProgram(static_cast<GLuint>(program));
    glBlendFuncSeparate(static_cast<GLenum>(blend_src_rgb), static_cast<GLenum>(blend_dst_rgb),
                        static_cast<GLenum>(blend_src_alpha), static_cast<GLenum>(blend_dst_alpha));
    auto restore = [](GLenum cap, GLboolean on) { on ? glEnable(cap) : glDisable(cap); };
    restore(GL_BLEND, blend);
    restore(GL_DEPTH_TEST, depth);
    restore(GL_CULL_FACE, cull);
    restore(GL_SCISSOR_TEST, scissor);
    restore(GL_STENCIL_TEST, stencil);
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  }
};

PanelLayer::PanelLayer() : gl_(std::make_unique<Gl>()) {}
PanelLayer::~PanelLayer() = default;

void PanelLayer::describe(const ImDrawData& d, uint64_t textures_version,
                          std::vector<std::byte>& out) {
  out.clear();
  append(out, textures_version);
  append(out, d.DisplayPos);
  append(out, d.DisplaySize);
  append(out, d.FramebufferScale);
  append(out, d.CmdListsCount);
  for (int l = 0; l < d.CmdListsCount; ++l) {
    const ImDrawList& list = *d.CmdLists[l];
    append_all(out, list.VtxBuffer);
    append_all(out, list.IdxBuffer);
    append(out, list.CmdBuffer.Size);
    for (const ImDrawCmd& c : list.CmdBuffer) {
      append(out, c.ClipRect);
      append(out, c.TextureId);
      append(out, c.VtxOffset);
      append(out, c.IdxOffset);
      append(out, c.ElemCount);
      append(out, c.UserCallback);
    }
  }
}

void PanelLayer::draw(ImDrawData& panel, uint64_t textures_version) {
  ++frames_;
  const int width = static_cast<int>(panel.DisplaySize.x * panel.FramebufferScale.x);
  const int height = static_cast<int>(panel.DisplaySize.y * panel.FramebufferScale.y);
  if (width <= 0 || height <= 0) return;
  if (!gl_->make(width, height)) {
    ++rasters_;
    ImGui_ImplOpenGL3_RenderDrawData(&panel);
    return;
  }
  describe(panel, textures_version, next_);
  if (next_ != drawn_ || rasters_ == 0) {
    ++rasters_;
    gl_->raster(panel);
    std::swap(drawn_, next_);
  }
  gl_->show();
}

}  // namespace sculpt::station
