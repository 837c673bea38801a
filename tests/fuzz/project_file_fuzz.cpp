// libFuzzer target: project files (.sculpt). The last four bytes of a
// project are the CRC-32 of everything before them, which random bytes
// almost never match: the target writes the right CRC over them first, so
// the mutations reach the description, the sizes and the compressed bricks
// behind the checksum (the structured mutation the reader must survive).
// Seeds: corpus/project_file (small projects the station wrote).

#include <zlib.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sculpt/station/project/project_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 4 || size > (size_t{1} << 24)) return 0;
  std::vector<uint8_t> bytes(data, data + size);
  const uint32_t crc = crc32(0, bytes.data(), static_cast<uInt>(size - 4));
  for (int i = 0; i < 4; ++i)
    bytes[size - 4 + size_t(i)] = static_cast<uint8_t>(crc >> (8 * i));
  (void)sculpt::station::parse_project(bytes, "fuzz.sculpt");
  return 0;
}
