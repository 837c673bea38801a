#include "sculpt/core/io/nrrd.h"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "sculpt/base/atomic_file.h"

namespace sculpt::core {
namespace {

// A header longer than this is not a header: stop before reading a whole
// binary file looking for the blank line.
constexpr size_t kMaxHeaderBytes = 1 << 20;

std::string trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return std::string(s.substr(first, last - first + 1));
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

Result<NrrdType> parse_type(const std::string& value) {
  const std::string v = lower(value);
  if (v == "uchar" || v == "unsigned char" || v == "uint8" || v == "uint8_t")
    return NrrdType::kUInt8;
  if (v == "float") return NrrdType::kFloat32;
  return Error("type '" + value + "' is not supported (uint8 or float)");
}

Result<glm::ivec3> parse_sizes(const std::string& value, const NrrdLimits& limits) {
  std::istringstream in(value);
  std::vector<std::string> words;
  for (std::string w; in >> w;)
    words.push_back(w);
  if (words.size() != 3)
    return Error("sizes: expected 3 numbers, got " + std::to_string(words.size()));
  int64_t s[3];
  for (int i = 0; i < 3; ++i) {
    const auto [end, ec] =
        std::from_chars(words[i].data(), words[i].data() + words[i].size(), s[i]);
    if (ec != std::errc() || end != words[i].data() + words[i].size() || s[i] < 1) {
      return Error("sizes: '" + words[i] + "' is not a positive integer");
    }
    if (s[i] > limits.max_voxels) return Error("sizes: " + words[i] + " is too large");
  }
  // Each factor is at most max_voxels (< 2^63), so check the product stepwise.
  if (s[0] * s[1] > limits.max_voxels || s[0] * s[1] > limits.max_voxels / s[2]) {
    return Error("sizes " + value + " are too large (more than " +
                 std::to_string(limits.max_voxels) + " voxels)");
  }
  return glm::ivec3(static_cast<int>(s[0]), static_cast<int>(s[1]), static_cast<int>(s[2]));
}

// Parses the header text (the magic line excluded) into fields.
Result<NrrdHeader> parse_header(const std::vector<std::string>& lines,
                                const std::filesystem::path& path, const NrrdLimits& limits) {
  std::map<std::string, std::string> fields;
  for (const std::string& line : lines) {
    if (line.empty() || line[0] == '#') continue;
    if (line.find(":=") != std::string::npos) continue;  // key/value pairs carry no layout
    const auto colon = line.find(": ");
    if (colon == std::string::npos)
      return Error("header line '" + line + "' is not 'field: value'");
    const std::string field = lower(trim(line.substr(0, colon)));
    if (!fields.emplace(field, trim(line.substr(colon + 2))).second) {
      return Error("field '" + field + "' appears twice");
    }
  }
  auto need = [&](const char* field) -> Result<std::string> {
    const auto it = fields.find(field);
    if (it == fields.end()) return Error(std::string("missing required field '") + field + "'");
    return it->second;
  };

  NrrdHeader h;
  auto dimension = need("dimension");
  if (!dimension) return dimension.error();
  if (trim(*dimension) != "3")
    return Error("dimension " + *dimension + " is not supported (3D volumes only)");
  auto type = need("type");
  if (!type) return type.error();
  auto parsed_type = parse_type(*type);
  if (!parsed_type) return parsed_type.error();
  h.type = *parsed_type;
  auto sizes = need("sizes");
  if (!sizes) return sizes.error();
  auto parsed_sizes = parse_sizes(*sizes, limits);
  if (!parsed_sizes) return parsed_sizes.error();
  h.dims = *parsed_sizes;
  auto encoding = need("encoding");
  if (!encoding) return encoding.error();
  const std::string enc = lower(*encoding);
  if (enc == "gzip" || enc == "gz") {
    h.gzip = true;
  } else if (enc != "raw") {
    return Error("encoding '" + *encoding + "' is not supported (raw or gzip)");
  }
  if (nrrd_type_size(h.type) > 1) {
    auto endian = need("endian");
    if (!endian) return endian.error();
    const std::string e = lower(*endian);
    if (e != "little" && e != "big")
      return Error("endian '" + *endian + "' is not 'little' or 'big'");
    h.big_endian = e == "big";
  }
  for (const char* skip : {"byte skip", "byteskip", "line skip", "lineskip"}) {
    const auto it = fields.find(skip);
    if (it != fields.end() && trim(it->second) != "0") {
      return Error(std::string("field '") + skip + "' is not supported");
    }
  }
  h.data_path = path;
  for (const char* name : {"data file", "datafile"}) {
    const auto it = fields.find(name);
    if (it == fields.end()) continue;
    if (it->second.find(' ') != std::string::npos || it->second == "LIST") {
      return Error("data file '" + it->second + "': only a single detached file is supported");
    }
    const std::filesystem::path detached(it->second);
    h.data_path = detached.is_absolute() ? detached : path.parent_path() / detached;
  }
  return h;
}

}  // namespace

const char* nrrd_type_name(NrrdType type) {
  return type == NrrdType::kUInt8 ? "uint8" : "float";
}
size_t nrrd_type_size(NrrdType type) {
  return type == NrrdType::kUInt8 ? 1 : 4;
}

struct NrrdReader::Impl {
  NrrdHeader header;
  std::string name;  // the path as the user gave it, for messages
  File file;
  int64_t slices_left = 0;
  bool failed = false;
  // gzip state
  z_stream zs{};
  bool zs_open = false;
  bool zs_done = false;
  std::vector<unsigned char> in_buffer;

  ~Impl() {
    if (zs_open) inflateEnd(&zs);
  }

  Status fail(const std::string& what) {
    failed = true;
    return Error(name + ": " + what);
  }

  Status read_raw(std::span<std::byte> out) {
    const size_t got = std::fread(out.data(), 1, out.size(), file.get());
    if (got != out.size()) return fail("truncated data (unexpected end of file)");
    return {};
  }

  Status read_gzip(std::span<std::byte> out) {
    zs.next_out = reinterpret_cast<Bytef*>(out.data());
    size_t want = out.size();
    while (want > 0) {
      // zlib counts in uInt; feed large outputs in pieces.
      const uInt chunk = static_cast<uInt>(std::min<size_t>(want, 1u << 30));
      zs.avail_out = chunk;
      while (zs.avail_out > 0) {
        if (zs_done) return fail("truncated gzip data (the stream ends before the sizes say)");
        if (zs.avail_in == 0) {
          const size_t got = std::fread(in_buffer.data(), 1, in_buffer.size(), file.get());
          if (got == 0) return fail("truncated gzip data (unexpected end of file)");
          zs.next_in = in_buffer.data();
          zs.avail_in = static_cast<uInt>(got);
        }
        const int rc = inflate(&zs, Z_NO_FLUSH);
        if (rc == Z_STREAM_END) {
          zs_done = true;
        } else if (rc != Z_OK) {
          return fail(std::string("corrupt gzip data (zlib: ") + (zs.msg ? zs.msg : "error") + ")");
        }
      }
      want -= chunk;
    }
    return {};
  }
};

NrrdReader::NrrdReader(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
NrrdReader::NrrdReader(NrrdReader&&) noexcept = default;
NrrdReader& NrrdReader::operator=(NrrdReader&&) noexcept = default;
NrrdReader::~NrrdReader() = default;

const NrrdHeader& NrrdReader::header() const {
  return impl_->header;
}

Result<NrrdReader> NrrdReader::open(const std::filesystem::path& path, const NrrdLimits& limits) {
  const std::string name = path.string();
  File file(std::fopen(name.c_str(), "rb"));
  if (!file) return Error(name + ": cannot open: " + std::strerror(errno));

  // Header lines up to the first blank line (or the end, for a detached .nhdr).
  std::vector<std::string> lines;
  std::string line;
  size_t header_bytes = 0;
  bool blank_seen = false;
  for (int c; (c = std::fgetc(file.get())) != EOF;) {
    if (++header_bytes > kMaxHeaderBytes)
      return Error(name + ": header does not end (no blank line)");
    if (c != '\n') {
      line.push_back(static_cast<char>(c));
      continue;
    }
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (lines.empty() && line.rfind("NRRD000", 0) != 0) break;
    if (line.empty()) {
      blank_seen = true;
      break;
    }
    lines.push_back(std::move(line));
    line.clear();
  }
  if (!blank_seen && !line.empty()) lines.push_back(std::move(line));  // last line without newline
  if (lines.empty() || lines[0].size() != 8 || lines[0].rfind("NRRD000", 0) != 0 ||
      lines[0][7] < '1' || lines[0][7] > '5') {
    return Error(name + ": not a NRRD file (it does not start with NRRD0001..NRRD0005)");
  }
  auto header = parse_header({lines.begin() + 1, lines.end()}, path, limits);
  if (!header) return header.error().in(name);

  auto impl = std::make_unique<Impl>();
  impl->name = name;
  impl->header = *header;
  impl->slices_left = header->dims.z;
  if (header->data_path != path) {
    impl->file.reset(std::fopen(header->data_path.string().c_str(), "rb"));
    if (!impl->file) {
      return Error(name + ": cannot open data file " + header->data_path.string() + ": " +
                   std::strerror(errno));
    }
    impl->header.data_offset = 0;
  } else {
    if (!blank_seen) return Error(name + ": header does not end with a blank line before the data");
    impl->header.data_offset = static_cast<int64_t>(header_bytes);
    impl->file = std::move(file);
  }

  if (header->gzip) {
    if (inflateInit2(&impl->zs, 15 + 32) != Z_OK)
      return Error(name + ": cannot start gzip decoding");
    impl->zs_open = true;
    impl->in_buffer.resize(1 << 16);
  } else {
    // Raw data must be exactly as long as the sizes say: checked before any
    // allocation, so a lying header cannot make us reserve gigabytes.
    std::error_code ec;
    const auto file_size =
        static_cast<int64_t>(std::filesystem::file_size(impl->header.data_path, ec));
    if (ec) return Error(name + ": cannot read the data's size: " + ec.message());
    const int64_t expected =
        voxel_count(header->dims) * static_cast<int64_t>(nrrd_type_size(header->type));
    const int64_t available = file_size - impl->header.data_offset;
    const std::string shape = std::to_string(header->dims.x) + "x" +
                              std::to_string(header->dims.y) + "x" +
                              std::to_string(header->dims.z) + " " + nrrd_type_name(header->type);
    if (available < expected) {
      return Error(name + ": truncated data: " + shape + " needs " + std::to_string(expected) +
                   " bytes, the file holds " + std::to_string(std::max<int64_t>(available, 0)));
    }
    if (available > expected) {
      return Error(name + ": " + std::to_string(available - expected) + " bytes more data than " +
                   shape + " needs (wrong sizes or type?)");
    }
  }
  return NrrdReader(std::move(impl));
}

Status NrrdReader::read_slices(int slices, std::span<std::byte> out) {
  Impl& s = *impl_;
  if (s.failed) return Error(s.name + ": reading after an error");
  const size_t elem = nrrd_type_size(s.header.type);
  assert(slices <= s.slices_left);
  assert(out.size() == static_cast<size_t>(slices) * s.header.dims.x * s.header.dims.y * elem);
  Status st = s.header.gzip ? s.read_gzip(out) : s.read_raw(out);
  if (!st) return st;
  s.slices_left -= slices;
  const bool host_big_endian = std::endian::native == std::endian::big;
  if (elem > 1 && s.header.big_endian != host_big_endian) {
    for (size_t i = 0; i < out.size(); i += elem)
      std::reverse(out.begin() + i, out.begin() + i + elem);
  }
  if (s.slices_left == 0 && s.header.gzip && !s.zs_done) {
    // The stream must end exactly where the sizes say.
    std::byte extra;
    s.zs.next_out = reinterpret_cast<Bytef*>(&extra);
    s.zs.avail_out = 1;
    if (s.zs.avail_in == 0) {
      const size_t got = std::fread(s.in_buffer.data(), 1, s.in_buffer.size(), s.file.get());
      s.zs.next_in = s.in_buffer.data();
      s.zs.avail_in = static_cast<uInt>(got);
    }
    const int rc = inflate(&s.zs, Z_NO_FLUSH);
    if (rc != Z_STREAM_END || s.zs.avail_out == 0) {
      return s.fail("gzip data is longer than the sizes say (wrong sizes or type?)");
    }
    s.zs_done = true;
  }
  if (s.slices_left == 0 && s.header.gzip) {
    // Nothing may follow the stream: bytes there are a second stream or a
    // damaged file, and ignoring them would read a different volume.
    char more;
    if (s.zs.avail_in > 0 || std::fread(&more, 1, 1, s.file.get()) == 1) {
      return s.fail("bytes follow the gzip data (a damaged or concatenated file)");
    }
  }
  return {};
}

namespace {

template <class T>
Result<DenseGrid<T>> read_whole(const std::filesystem::path& path, const NrrdLimits& limits,
                                NrrdType want) {
  auto reader = NrrdReader::open(path, limits);
  if (!reader) return reader.error();
  const NrrdHeader& h = reader->header();
  if (h.type != want) {
    return Error(path.string() + ": holds " + nrrd_type_name(h.type) + " voxels, expected " +
                 nrrd_type_name(want));
  }
  // Grow the grid a slab at a time: a gzip stream that ends early stops the
  // read before the full size (which a hostile header can inflate) is reserved.
  std::vector<T> values;
  const size_t slice = static_cast<size_t>(h.dims.x) * h.dims.y;
  const int slab = static_cast<int>(std::max<size_t>(1, (size_t{64} << 20) / (slice * sizeof(T))));
  for (int z = 0; z < h.dims.z; z += slab) {
    const int n = std::min(slab, h.dims.z - z);
    const size_t at = values.size();
    values.resize(at + slice * n);
    Status st = reader->read_slices(n, std::as_writable_bytes(std::span(values).subspan(at)));
    if (!st) return st.error();
  }
  DenseGrid<T> grid(h.dims);
  grid.values() = std::move(values);
  return grid;
}

template <class T>
Status write_whole(const std::filesystem::path& path, const DenseGrid<T>& grid, NrrdType type) {
  AtomicFileWriter out(path);
  if (!out.ok()) return out.error();
  out.write(nrrd_header_text(grid.dims(), type));
  static_assert(std::endian::native == std::endian::little, "NRRD output is written little endian");
  out.write(grid.data(), grid.size() * sizeof(T));
  return out.commit();
}

}  // namespace

Result<DenseGrid<uint8_t>> read_nrrd_u8(const std::filesystem::path& path,
                                        const NrrdLimits& limits) {
  return read_whole<uint8_t>(path, limits, NrrdType::kUInt8);
}
Result<DenseGrid<float>> read_nrrd_f32(const std::filesystem::path& path,
                                       const NrrdLimits& limits) {
  return read_whole<float>(path, limits, NrrdType::kFloat32);
}

std::string nrrd_header_text(glm::ivec3 dims, NrrdType type) {
  std::string h = "NRRD0004\n# written by sculpt; voxel (x, y, z) at x, y, z\n";
  h += std::string("type: ") + nrrd_type_name(type) + "\n";
  h += "dimension: 3\n";
  h += "sizes: " + std::to_string(dims.x) + " " + std::to_string(dims.y) + " " +
       std::to_string(dims.z) + "\n";
  h += "spacings: 1 1 1\n";
  if (nrrd_type_size(type) > 1) h += "endian: little\n";
  h += "encoding: raw\n\n";
  return h;
}

Status write_nrrd(const std::filesystem::path& path, const DenseGrid<uint8_t>& grid) {
  return write_whole(path, grid, NrrdType::kUInt8);
}
Status write_nrrd(const std::filesystem::path& path, const DenseGrid<float>& grid) {
  return write_whole(path, grid, NrrdType::kFloat32);
}

}  // namespace sculpt::core
