#pragma once
// NRRD volumes (http://teem.sourceforge.net/nrrd/format.html), the project's
// volume format: 3D, uint8 density or float32 distance, x fastest.
//
// Reading accepts what the reference library writes: attached or detached
// ("data file: NAME") data; raw, gzip, bzip2, ascii or hex encoding; uint8,
// int16, uint16, float or double voxels, little or big endian; and ignores
// fields it does not need (space, spacings, kinds, key/value pairs).
// Everything is checked against the header before anything large is
// allocated: sizes against NrrdLimits, raw and text data against the file's
// length; compressed data is read a slab at a time, so a stream that ends
// early stops the read before the declared size is reserved. A volume of
// other voxels than uint8 becomes density through a DensityWindow (CT data
// is 16-bit). Writing produces NRRD0004, raw, little endian, through
// AtomicFileWriter (no partial file on failure).

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>

#include <glm/vec3.hpp>

#include "sculpt/base/result.h"
#include "sculpt/core/grid/dense_grid.h"

namespace sculpt::core {

enum class NrrdType { kUInt8, kInt16, kUInt16, kFloat32, kFloat64 };
enum class NrrdEncoding { kRaw, kGzip, kBzip2, kAscii, kHex };

/// Name of a type as NRRD writes it ("uint8", "int16", "uint16", "float", "double").
const char* nrrd_type_name(NrrdType type);
size_t nrrd_type_size(NrrdType type);

struct NrrdLimits {
  /// Largest voxel count accepted (default 2^32, e.g. 2048 x 2048 x 1024).
  int64_t max_voxels = int64_t{1} << 32;
};

/// How the values of a volume become density: `lo` and below 0, `hi` and
/// above 255, linear between (rounded). The command line's --window LO,HI,
/// or --data-iso V (window_around()).
struct DensityWindow {
  double lo = 0.0;
  double hi = 255.0;
};

struct NrrdHeader {
  glm::ivec3 dims{0};
  NrrdType type = NrrdType::kUInt8;
  NrrdEncoding encoding = NrrdEncoding::kRaw;
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
  /// The next `slices` z-slices as density: uint8 voxels as they are when
  /// `window` is null, any type through `window` otherwise (null for other
  /// types is an error naming the options that map them).
  Status read_density_slices(int slices, const DensityWindow* window, std::span<uint8_t> out);

 private:
  struct Impl;
  explicit NrrdReader(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// --data-iso V: the narrowest window centred on `iso` that holds every value
/// of the file, so none is clamped and the surface stays where the data puts
/// it (to 1/255 of the window). Reads the file once for its range.
Result<DensityWindow> window_around(const std::filesystem::path& path, double iso,
                                    const NrrdLimits& limits = {});
/// A whole volume as density (read_density_slices()).
Result<DenseGrid<uint8_t>> read_nrrd_density(const std::filesystem::path& path,
                                             const DensityWindow* window,
                                             const NrrdLimits& limits = {});

/// Reads a whole uint8 volume. Other types are refused with a clear error.
Result<DenseGrid<uint8_t>> read_nrrd_u8(const std::filesystem::path& path,
                                        const NrrdLimits& limits = {});
/// Reads a whole float32 volume (double voxels are rounded to float). Other
/// types are refused with a clear error.
Result<DenseGrid<float>> read_nrrd_f32(const std::filesystem::path& path,
                                       const NrrdLimits& limits = {});

/// Writes a NRRD file: all of it, or nothing.
Status write_nrrd(const std::filesystem::path& path, const DenseGrid<uint8_t>& grid);
Status write_nrrd(const std::filesystem::path& path, const DenseGrid<float>& grid);

/// The header text write_nrrd() emits (ends with the blank line).
std::string nrrd_header_text(glm::ivec3 dims, NrrdType type);

}  // namespace sculpt::core
