#pragma once
// NRRD volumes (http://teem.sourceforge.net/nrrd/format.html), the project's
// volume format: 3D, uint8 density or float32 distance, x fastest.
//
// Reading accepts attached or detached ("data file: NAME") data, raw or gzip
// encoding, little or big endian, and ignores fields it does not need (space,
// spacings, kinds, key/value pairs). Everything is checked against the header
// before anything large is allocated: sizes against NrrdLimits, raw data
// against the file's length. Writing produces NRRD0004, raw, little endian,
// through AtomicFileWriter (no partial file on failure).

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>

#include <glm/vec3.hpp>

#include "sculpt/core/grid/dense_grid.h"
#include "sculpt/base/result.h"

namespace sculpt::core {

enum class NrrdType { kUInt8, kFloat32 };

/// Name of a type as NRRD writes it ("uint8", "float").
const char* nrrd_type_name(NrrdType type);
size_t nrrd_type_size(NrrdType type);

struct NrrdLimits {
  /// Largest voxel count accepted (default 2^32, e.g. 2048 x 2048 x 1024).
  int64_t max_voxels = int64_t{1} << 32;
};

struct NrrdHeader {
  glm::ivec3 dims{0};
  NrrdType type = NrrdType::kUInt8;
  bool gzip = false;
  bool big_endian = false;
  /// Where the data is: the file itself or a detached data file.
  std::filesystem::path data_path;
  /// Byte offset of the data in data_path.
  int64_t data_offset = 0;
};

/// Streams a NRRD file's voxels slice by slice, so a volume far larger than
/// memory as a dense array can be brick-encoded on the fly.
class NrrdReader {
 public:
  /// Parses and checks the header; errors name the file and the field.
  static Result<NrrdReader> open(const std::filesystem::path& path, const NrrdLimits& limits = {});
  NrrdReader(NrrdReader&&) noexcept;
  NrrdReader& operator=(NrrdReader&&) noexcept;
  ~NrrdReader();

  const NrrdHeader& header() const;
  /// Reads the next `slices` z-slices (slices * dims.x * dims.y values of the
  /// header's type, host byte order) into `out`. Errors on truncated or
  /// corrupt data; after an error the reader is spent.
  Status read_slices(int slices, std::span<std::byte> out);

 private:
  struct Impl;
  explicit NrrdReader(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// Reads a whole uint8 volume. A float32 file is refused with a clear error.
Result<DenseGrid<uint8_t>> read_nrrd_u8(const std::filesystem::path& path,
                                        const NrrdLimits& limits = {});
/// Reads a whole float32 volume. A uint8 file is refused with a clear error.
Result<DenseGrid<float>> read_nrrd_f32(const std::filesystem::path& path,
                                       const NrrdLimits& limits = {});

/// Writes a NRRD file: all of it, or nothing.
Status write_nrrd(const std::filesystem::path& path, const DenseGrid<uint8_t>& grid);
Status write_nrrd(const std::filesystem::path& path, const DenseGrid<float>& grid);

/// The header text write_nrrd() emits (ends with the blank line).
std::string nrrd_header_text(glm::ivec3 dims, NrrdType type);

}  // namespace sculpt::core
