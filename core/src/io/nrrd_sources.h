#pragma once
// Internal to NRRD reading: the data's bytes, whatever the encoding, as the
// typed values in the file's byte order (ascii: host order, the reader does
// not swap). One class per encoding the reference library (teem) writes:
// raw, gzip, bzip2, ascii and hex.

#include <cstddef>
#include <cstdio>
#include <memory>
#include <span>

#include "sculpt/base/result.h"
#include "sculpt/core/io/nrrd.h"

namespace sculpt::core::detail {

class NrrdSource {
 public:
  virtual ~NrrdSource() = default;
  /// Fills `out` with the next bytes of data; an error says what is wrong
  /// with the data (the reader names the file).
  virtual Status read(std::span<std::byte> out) = 0;
  /// After the last value: the data must end here (nothing but whitespace
  /// after text, no second stream after a compressed one).
  virtual Status finish() = 0;
};

/// A source reading `file` (positioned at the data) in `encoding`, for
/// values of `type`. The source does not own the file.
std::unique_ptr<NrrdSource> make_nrrd_source(NrrdEncoding encoding, NrrdType type, std::FILE* file);

}  // namespace sculpt::core::detail
