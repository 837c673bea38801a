#include "sculpt/station/render/software_renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <stb_image_write.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "sculpt/base/atomic_file.h"

namespace sculpt::station {
namespace {

struct Camera {
  glm::vec3 centre, right, up, back;  // back points toward the camera
  float scale;                        // pixels per voxel
  float cx, cy;
};

Camera frame(const SoftwareView& v) {
  Camera c;
  c.centre = (v.box_lo + v.box_hi) * 0.5f;
  c.back = glm::normalize(v.toward_camera);
  const glm::vec3 world_up(0, 1, 0);
  c.right = glm::normalize(glm::cross(world_up, c.back));
  c.up = glm::cross(c.back, c.right);
  // Fit the box's bounding sphere with a margin, whatever the direction.
  const float radius = glm::length(v.box_hi - v.box_lo) * 0.5f;
  c.scale = 0.95f * static_cast<float>(std::min(v.width, v.height)) / (2.0f * radius);
  c.cx = static_cast<float>(v.width) * 0.5f;
  c.cy = static_cast<float>(v.height) * 0.5f;
  return c;
}

glm::vec3 background(int y, int height) {
  const float t = static_cast<float>(y) / static_cast<float>(std::max(height - 1, 1));
  return glm::mix(glm::vec3(0.30f, 0.33f, 0.38f), glm::vec3(0.12f, 0.13f, 0.15f), t);
}

}  // namespace

SoftwareView view_of(const core::Mesh& mesh, glm::vec3 box_lo, glm::vec3 box_hi) {
  SoftwareView v;
  v.box_lo = box_lo;
  v.box_hi = box_hi;
  if (!mesh.positions.empty()) {
    v.box_lo = v.box_hi = mesh.positions.front();
    for (const glm::vec3& p : mesh.positions) {
      v.box_lo = glm::min(v.box_lo, p);
      v.box_hi = glm::max(v.box_hi, p);
    }
  }
  return v;
}

RgbImage render_mesh(const core::Mesh& mesh, const SoftwareView& view) {
  const Camera cam = frame(view);
  RgbImage img{view.width, view.height,
               std::vector<uint8_t>(static_cast<size_t>(view.width) * view.height * 3)};
  std::vector<float> depth(static_cast<size_t>(view.width) * view.height,
                           -std::numeric_limits<float>::infinity());
  std::vector<glm::vec3> colour(depth.size());
  for (int y = 0; y < view.height; ++y)
    std::fill_n(colour.begin() + static_cast<ptrdiff_t>(y) * view.width, view.width,
                background(y, view.height));

  // Studio lighting: a warm key from the upper left front, a cool fill from
  // the right, ambient; clay-coloured material.
  const glm::vec3 key_dir = glm::normalize(-0.5f * cam.right + 0.7f * cam.up + 0.6f * cam.back);
  const glm::vec3 fill_dir = glm::normalize(0.8f * cam.right - 0.1f * cam.up + 0.4f * cam.back);
  const glm::vec3 clay(0.85f, 0.74f, 0.62f);

  const bool have_normals = mesh.normals.size() == mesh.positions.size();
  for (const glm::uvec3& t : mesh.triangles) {
    glm::vec3 p[3], s[3];
    for (int k = 0; k < 3; ++k) {
      p[k] = mesh.positions[t[k]];
      const glm::vec3 d = p[k] - cam.centre;
      s[k] = {cam.cx + glm::dot(d, cam.right) * cam.scale, cam.cy - glm::dot(d, cam.up) * cam.scale,
              glm::dot(d, cam.back)};
    }
    // Counter-clockwise seen from outside: in screen space (y down) a front
    // face has negative signed area.
    const float area =
        (s[1].x - s[0].x) * (s[2].y - s[0].y) - (s[2].x - s[0].x) * (s[1].y - s[0].y);
    if (area >= 0.0f) continue;
    const glm::vec3 face_n = glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({s[0].x, s[1].x, s[2].x}))));
    const int x1 =
        std::min(view.width - 1, static_cast<int>(std::ceil(std::max({s[0].x, s[1].x, s[2].x}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({s[0].y, s[1].y, s[2].y}))));
    const int y1 =
        std::min(view.height - 1, static_cast<int>(std::ceil(std::max({s[0].y, s[1].y, s[2].y}))));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const float px = static_cast<float>(x) + 0.5f, py = static_cast<float>(y) + 0.5f;
        // Barycentric weights from edge functions.
        const float w0 = ((s[1].x - px) * (s[2].y - py) - (s[2].x - px) * (s[1].y - py)) / area;
        const float w1 = ((s[2].x - px) * (s[0].y - py) - (s[0].x - px) * (s[2].y - py)) / area;
        const float w2 = 1.0f - w0 - w1;
        if (w0 < 0 || w1 < 0 || w2 < 0) continue;
        const float z = w0 * s[0].z + w1 * s[1].z + w2 * s[2].z;
        const size_t i = static_cast<size_t>(y) * view.width + x;
        if (z <= depth[i]) continue;
        depth[i] = z;
        glm::vec3 n = have_normals ? w0 * mesh.normals[t[0]] + w1 * mesh.normals[t[1]] +
                                         w2 * mesh.normals[t[2]]
                                   : face_n;
        n = glm::length(n) > 0 ? glm::normalize(n) : face_n;
        const float key = std::max(0.0f, glm::dot(n, key_dir));
        const float fill = std::max(0.0f, glm::dot(n, fill_dir));
        const float rim = std::pow(1.0f - std::max(0.0f, glm::dot(n, cam.back)), 3.0f);
        colour[i] =
            clay * (0.18f + 0.75f * key + 0.22f * fill * glm::vec3(0.8f, 0.9f, 1.1f)) + 0.15f * rim;
      }
    }
  }
  for (size_t i = 0; i < colour.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      img.rgb[3 * i + k] =
          static_cast<uint8_t>(std::clamp(colour[i][k], 0.0f, 1.0f) * 255.0f + 0.5f);
    }
  }
  return img;
}

double coverage(const RgbImage& image, const SoftwareView& view) {
  const RgbImage empty = render_mesh(core::Mesh{}, view);
  int64_t covered = 0;
  const int64_t pixels = int64_t{image.width} * image.height;
  for (int64_t i = 0; i < pixels; ++i) {
    covered += image.rgb[3 * i] != empty.rgb[3 * i] ||
               image.rgb[3 * i + 1] != empty.rgb[3 * i + 1] ||
               image.rgb[3 * i + 2] != empty.rgb[3 * i + 2];
  }
  return static_cast<double>(covered) / static_cast<double>(pixels);
}

Status write_png(const std::filesystem::path& path, const RgbImage& image) {
  std::vector<uint8_t> bytes;
  auto sink = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<uint8_t>*>(context);
    const auto* b = static_cast<const uint8_t*>(data);
    out->insert(out->end(), b, b + size);
  };
  if (stbi_write_png_to_func(sink, &bytes, image.width, image.height, 3, image.rgb.data(),
                             image.width * 3) == 0) {
    return Error(path.string() + ": PNG encoding failed");
  }
  AtomicFileWriter out(path);
  out.write(bytes.data(), bytes.size());
  return out.commit();
}

}  // namespace sculpt::station
