// libFuzzer target: the NRRD reader (header; raw, gzip, bzip2, ascii and hex
// data; every voxel type, also mapped to density through a window), through
// a file as users give it. Seeds: corpus/nrrd.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "sculpt/core/io/nrrd.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = "/tmp/sculpt_nrrd_fuzz_" + std::to_string(::getpid()) + ".nrrd";
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return 0;
  std::fwrite(data, 1, size, f);
  std::fclose(f);
  // A small limit keeps each run fast; the reader must honour it.
  sculpt::core::NrrdLimits limits;
  limits.max_voxels = 1 << 20;
  auto u8 = sculpt::core::read_nrrd_u8(path, limits);
  auto f32 = sculpt::core::read_nrrd_f32(path, limits);
  if (u8.ok() && sculpt::core::voxel_count(u8->dims()) > limits.max_voxels) __builtin_trap();
  (void)f32;
  const sculpt::core::DensityWindow window{-1000.0, 1000.0};
  auto mapped = sculpt::core::read_nrrd_density(path, &window, limits);
  if (mapped.ok() && sculpt::core::voxel_count(mapped->dims()) > limits.max_voxels)
    __builtin_trap();
  return 0;
}
