// libFuzzer target: the .vdb reader (OpenVDB's stream reader in a child
// process, then our checks of grid type, transform, size and values, and the
// parent's reading of the child's answer), from memory through the same
// std::istream path a file takes. Seeds: corpus/vdb_file (written by `sculpt
// wavelet ... -o X.vdb` and tests/data/vdb/make_bad_vdb.py).

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <sstream>
#include <string>

#include "sculpt/core/files/vdb_file.h"
#include "sculpt/core/grid/dense_grid.h"

// OpenVDB allocates what a length in the file says before it reads the bytes
// (a metadata string, a compressed block): a corrupt file asks for gigabytes
// or terabytes. On a real machine a request it cannot grant throws
// std::bad_alloc, which read_vdb() reports as one line; under ASan it is a
// fatal report instead. So this target is a machine with 256 MiB to give a
// single allocation: larger requests throw, as they would there, and the
// fuzzer goes on looking for what is really wrong (ASan still checks every
// byte: these call malloc and free).
namespace {
constexpr size_t kMaxAllocation = size_t{256} << 20;

void* allocate(size_t n) {
  if (n > kMaxAllocation) throw std::bad_alloc();
  if (void* p = std::malloc(n != 0 ? n : 1)) return p;
  throw std::bad_alloc();
}

void* allocate_aligned(size_t n, std::align_val_t align) {
  const auto a = static_cast<size_t>(align);
  if (n > kMaxAllocation) throw std::bad_alloc();
  if (void* p = std::aligned_alloc(a, (n + a - 1) / a * a + (n == 0 ? a : 0))) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(size_t n) {
  return allocate(n);
}
void* operator new[](size_t n) {
  return allocate(n);
}
void* operator new(size_t n, std::align_val_t a) {
  return allocate_aligned(n, a);
}
void* operator new[](size_t n, std::align_val_t a) {
  return allocate_aligned(n, a);
}
void* operator new(size_t n, const std::nothrow_t&) noexcept {
  return n > kMaxAllocation ? nullptr : std::malloc(n != 0 ? n : 1);
}
void* operator new[](size_t n, const std::nothrow_t&) noexcept {
  return n > kMaxAllocation ? nullptr : std::malloc(n != 0 ? n : 1);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, size_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete(void* p, size_t, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, size_t, std::align_val_t) noexcept {
  std::free(p);
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size), std::ios::binary);
  // A small limit keeps each run fast; the reader must honour it. OpenVDB
  // parses in a child process (read_vdb()): its crashes (Debian's 10.0.1
  // overflows a heap buffer in io::bloscFromStream) are an error here, with
  // the child's sanitizer report sent to /dev/null; a fault in the parent's
  // side (the pipe, the checks, the copy) still stops the fuzzer.
  sculpt::core::VdbLimits limits;
  limits.max_voxels = 1 << 20;
  limits.reader_stderr_to_null = true;
  limits.reader_cpu_seconds = 5;  // a file that keeps OpenVDB busy is refused sooner
  auto grids = sculpt::core::read_vdb(in, "fuzz.vdb", limits);
  if (!grids.ok()) return 0;
  const glm::ivec3 dims = grids->density ? grids->density->dims() : grids->surface->dims();
  if (sculpt::core::voxel_count(dims) > limits.max_voxels) __builtin_trap();
  if (!grids->density && !grids->surface) __builtin_trap();
  return 0;
}
