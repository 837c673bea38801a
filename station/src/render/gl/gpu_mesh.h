#pragma once
// One indexed triangle mesh on the GPU: positions and normals interleaved in
// one buffer, 32-bit indices in another, bound in one vertex array.

#include <cstdint>

#include "render/gl/gl_api.h"
#include "sculpt/core/mesh/mesh.h"

namespace sculpt::station::gl {

class GpuMesh {
 public:
  GpuMesh() = default;
  ~GpuMesh();
  GpuMesh(GpuMesh&& other) noexcept;
  GpuMesh& operator=(GpuMesh&& other) noexcept;
  GpuMesh(const GpuMesh&) = delete;
  GpuMesh& operator=(const GpuMesh&) = delete;

  /// Replaces the contents (normals taken from the mesh, zero when absent).
  void upload(const core::Mesh& mesh);
  void draw() const;
  bool empty() const { return index_count_ == 0; }
  int64_t triangles() const { return index_count_ / 3; }

 private:
  void release();
  GLuint vao_ = 0, vbo_ = 0, ebo_ = 0;
  GLsizei index_count_ = 0;
};

}  // namespace sculpt::station::gl
