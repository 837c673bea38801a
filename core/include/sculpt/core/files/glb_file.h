#pragma once
// Binary glTF 2.0 (.glb) meshes from Blender, game engines and 3D scanners,
// for `sculpt voxelize`, `import` and `mesh --check` (the writer is
// core/mesh/mesh_io.h). Read: the default scene (its `scene`, else the
// first; without scenes every mesh once), each node's matrix or
// translation-rotation-scale applied down the node tree, every triangle
// primitive (TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN) joined into one Mesh:
// POSITION as float VEC3, NORMAL as float VEC3 (kept when every primitive
// has them), indices as unsigned byte, short or int (none: in order).
// Points and lines are skipped. Coordinates are returned as stored (glTF
// means metres; our own .glb files hold voxel units).
//
// Refused, with one message naming the file and the fault: a file that is
// not GLB version 2 or whose header, chunks or length disagree; JSON that
// does not parse or misses a required field; buffers outside the BIN chunk
// (URIs); an accessor of another component type or shape, reaching past its
// buffer view, or a view past its buffer; sparse accessors; an index past
// the vertices; a node reached twice (a cycle); any extensionsRequired
// (Draco, meshopt and quantized meshes are not decoded); a mesh larger than
// GlbLimits; no triangles; coordinates that are not finite.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "sculpt/base/result.h"
#include "sculpt/core/mesh/mesh.h"

namespace sculpt::core {

struct GlbLimits {
  /// Largest file read, bytes (GLB's own length field is 32-bit).
  int64_t max_file_bytes = int64_t{1} << 32;
  /// Most triangles and most vertices in the joined mesh (a node tree can
  /// instance one mesh many times, so a small file could ask for gigabytes):
  /// 2^26, 67 million, some 280 times the 512^3 demo head, about 2.4 GB of
  /// mesh at the most.
  int64_t max_triangles = int64_t{1} << 26;
  int64_t max_vertices = int64_t{1} << 26;
  /// Deepest node tree.
  int max_node_depth = 256;
};

/// Reads the .glb at `path`; errors name `path`.
Result<Mesh> read_glb(const std::filesystem::path& path, const GlbLimits& limits = {});
/// The same from the file's bytes; errors name `name`.
Result<Mesh> read_glb(std::string_view bytes, const std::string& name,
                      const GlbLimits& limits = {});

}  // namespace sculpt::core
