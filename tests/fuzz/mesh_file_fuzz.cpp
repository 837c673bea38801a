// libFuzzer target: the mesh reader (PLY ascii and binary, OBJ, STL ascii
// and binary) through a file as users give it; the first byte picks the
// extension. Seeds: corpus/mesh_file (the first byte of each is 0, 1 or 2).

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "sculpt/core/mesh/mesh_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  static const char* const kExtensions[] = {".ply", ".obj", ".stl"};
  const std::string path =
      "/tmp/sculpt_mesh_fuzz_" + std::to_string(::getpid()) + kExtensions[data[0] % 3];
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return 0;
  std::fwrite(data + 1, 1, size - 1, f);
  std::fclose(f);
  auto mesh = sculpt::core::read_mesh(path);
  (void)mesh;
  std::remove(path.c_str());
  return 0;
}
