// libFuzzer target: the .glb (binary glTF 2.0) mesh reader on the file's
// bytes as users give them: the GLB container, the JSON, the accessors and
// the node tree. Seeds: corpus/glb_file (a tetrahedron as we write it, one
// under a node tree with a triangle strip, one with normals).

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "sculpt/core/files/glb_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  sculpt::core::GlbLimits limits;
  limits.max_triangles = 1 << 20;  // a small mesh instanced a million times is refused, not built
  limits.max_vertices = 1 << 20;
  auto mesh = sculpt::core::read_glb(std::string_view(reinterpret_cast<const char*>(data), size),
                                     "fuzz.glb", limits);
  (void)mesh;
  return 0;
}
