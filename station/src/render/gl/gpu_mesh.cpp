#include "render/gl/gpu_mesh.h"

#include <utility>
#include <vector>

namespace sculpt::station::gl {

GpuMesh::~GpuMesh() {
  release();
}

GpuMesh::GpuMesh(GpuMesh&& o) noexcept
    : vao_(std::exchange(o.vao_, 0)),
      vbo_(std::exchange(o.vbo_, 0)),
      ebo_(std::exchange(o.ebo_, 0)),
      index_count_(std::exchange(o.index_count_, 0)) {}

GpuMesh& GpuMesh::operator=(GpuMesh&& o) noexcept {
  if (this != &o) {
    release();
    vao_ = std::exchange(o.vao_, 0);
    vbo_ = std::exchange(o.vbo_, 0);
    ebo_ = std::exchange(o.ebo_, 0);
    index_count_ = std::exchange(o.index_count_, 0);
  }
  return *this;
}

void GpuMesh::release() {
  if (vao_ != 0) glDeleteVertexArrays(1, &vao_);
  if (vbo_ != 0) glDeleteBuffers(1, &vbo_);
  if (ebo_ != 0) glDeleteBuffers(1, &ebo_);
  vao_ = vbo_ = ebo_ = 0;
  index_count_ = 0;
}

void GpuMesh::upload(const core::Mesh& mesh) {
  index_count_ = static_cast<GLsizei>(mesh.triangles.size() * 3);
  if (index_count_ == 0) return;  // keeps the buffers for the next upload
  if (vao_ == 0) {
    glGenVertexArrays(1, &vao_);
    glGenBuffers(1, &vbo_);
    glGenBuffers(1, &ebo_);
    glBindVertexArray(vao_);
    glBindBuffer(GL_ARRAY_BUFFER, vbo_);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                          reinterpret_cast<const void*>(3 * sizeof(float)));
  }
  std::vector<float> vertices;
  vertices.reserve(mesh.positions.size() * 6);
  const bool normals = mesh.normals.size() == mesh.positions.size();
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3 p = mesh.positions[i];
    const glm::vec3 n = normals ? mesh.normals[i] : glm::vec3(0.0f);
    vertices.insert(vertices.end(), {p.x, p.y, p.z, n.x, n.y, n.z});
  }
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(float)),
               vertices.data(), GL_DYNAMIC_DRAW);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(mesh.triangles.size() * sizeof(glm::uvec3)),
               mesh.triangles.data(), GL_DYNAMIC_DRAW);
  glBindVertexArray(0);
}

void GpuMesh::draw() const {
  if (index_count_ == 0) return;
  glBindVertexArray(vao_);
  glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
}

}  // namespace sculpt::station::gl
