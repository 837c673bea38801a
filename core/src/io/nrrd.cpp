#include "sculpt/core/io/nrrd.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "io/nrrd_sources.h"
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
  // Every spelling the NRRD format defines for these types.
  const std::string v = lower(value);
  for (const char* name : {"uchar", "unsigned char", "uint8", "uint8_t"})
    if (v == name) return NrrdType::kUInt8;
  for (const char* name :
       {"short", "short int", "signed short", "signed short int", "int16", "int16_t"})
    if (v == name) return NrrdType::kInt16;
  for (const char* name : {"ushort", "unsigned short", "unsigned short int", "uint16", "uint16_t"})
    if (v == name) return NrrdType::kUInt16;
  if (v == "float") return NrrdType::kFloat32;
  if (v == "double") return NrrdType::kFloat64;
  return Error("type '" + value + "' is not supported (uint8, int16, uint16, float or double)");
}

Result<NrrdEncoding> parse_encoding(const std::string& value) {
  const std::string v = lower(value);
  if (v == "raw") return NrrdEncoding::kRaw;
  if (v == "gzip" || v == "gz") return NrrdEncoding::kGzip;
  if (v == "bzip2" || v == "bz2") return NrrdEncoding::kBzip2;
  if (v == "ascii" || v == "txt" || v == "text") return NrrdEncoding::kAscii;
  if (v == "hex") return NrrdEncoding::kHex;
  return Error("encoding '" + value + "' is not supported (raw, gzip, bzip2, ascii or hex)");
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
  auto parsed_encoding = parse_encoding(*encoding);
  if (!parsed_encoding) return parsed_encoding.error();
  h.encoding = *parsed_encoding;
  // Text gives each value in its own digits: no byte order.
  if (nrrd_type_size(h.type) > 1 && h.encoding != NrrdEncoding::kAscii) {
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
  switch (type) {
    case NrrdType::kUInt8:
      return "uint8";
    case NrrdType::kInt16:
      return "int16";
    case NrrdType::kUInt16:
      return "uint16";
    case NrrdType::kFloat32:
      return "float";
    case NrrdType::kFloat64:
      return "double";
  }
  return "?";
}
size_t nrrd_type_size(NrrdType type) {
  switch (type) {
    case NrrdType::kUInt8:
      return 1;
    case NrrdType::kInt16:
    case NrrdType::kUInt16:
      return 2;
    case NrrdType::kFloat32:
      return 4;
    case NrrdType::kFloat64:
      return 8;
  }
  return 1;
}

struct NrrdReader::Impl {
  NrrdHeader header;
  std::string name;  // the path as the user gave it, for messages
  File file;
  std::unique_ptr<detail::NrrdSource> source;
  int64_t slices_left = 0;
  bool failed = false;
  std::vector<std::byte> typed;  // read_density_slices(): the values as stored

  Status fail(const std::string& what) {
    failed = true;
    return Error(name + ": " + what);
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

  const NrrdEncoding encoding = header->encoding;
  if (encoding != NrrdEncoding::kGzip && encoding != NrrdEncoding::kBzip2) {
    // Checked before any allocation, so a lying header cannot make us
    // reserve gigabytes: raw data is exactly as long as the sizes say, hex
    // has two digits per byte, ascii at least a digit and a separator per
    // value (the last one's separator may be missing).
    std::error_code ec;
    const auto file_size =
        static_cast<int64_t>(std::filesystem::file_size(impl->header.data_path, ec));
    if (ec) return Error(name + ": cannot read the data's size: " + ec.message());
    const int64_t voxels = voxel_count(header->dims);
    const int64_t bytes = voxels * static_cast<int64_t>(nrrd_type_size(header->type));
    const int64_t available = file_size - impl->header.data_offset;
    const std::string shape = std::to_string(header->dims.x) + "x" +
                              std::to_string(header->dims.y) + "x" +
                              std::to_string(header->dims.z) + " " + nrrd_type_name(header->type);
    const int64_t least = encoding == NrrdEncoding::kRaw   ? bytes
                          : encoding == NrrdEncoding::kHex ? 2 * bytes
                                                           : 2 * voxels - 1;
    if (available < least) {
      return Error(name + ": truncated data: " + shape + " needs " +
                   (encoding == NrrdEncoding::kRaw ? "" : "at least ") + std::to_string(least) +
                   " bytes, the file holds " + std::to_string(std::max<int64_t>(available, 0)));
    }
    if (encoding == NrrdEncoding::kRaw && available > bytes) {
      return Error(name + ": " + std::to_string(available - bytes) + " bytes more data than " +
                   shape + " needs (wrong sizes or type?)");
    }
  }
  impl->source = detail::make_nrrd_source(encoding, header->type, impl->file.get());
  return NrrdReader(std::move(impl));
}

Status NrrdReader::read_slices(int slices, std::span<std::byte> out) {
  Impl& s = *impl_;
  if (s.failed) return Error(s.name + ": reading after an error");
  const size_t elem = nrrd_type_size(s.header.type);
  assert(slices <= s.slices_left);
  assert(out.size() == static_cast<size_t>(slices) * s.header.dims.x * s.header.dims.y * elem);
  if (Status st = s.source->read(out); !st) return s.fail(st.error().message());
  s.slices_left -= slices;
  const bool host_big_endian = std::endian::native == std::endian::big;
  if (elem > 1 && s.header.encoding != NrrdEncoding::kAscii &&
      s.header.big_endian != host_big_endian) {
    for (size_t i = 0; i < out.size(); i += elem)
      std::reverse(out.begin() + i, out.begin() + i + elem);
  }
  if (s.slices_left == 0) {
    if (Status st = s.source->finish(); !st) return s.fail(st.error().message());
  }
  return {};
}

namespace {

template <class T>
double value_at(const std::byte* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return static_cast<double>(v);
}

// Value i of `typed` (host order) as a double.
double typed_value(NrrdType type, const std::byte* typed, size_t i) {
  switch (type) {
    case NrrdType::kUInt8:
      return value_at<uint8_t>(typed + i);
    case NrrdType::kInt16:
      return value_at<int16_t>(typed + 2 * i);
    case NrrdType::kUInt16:
      return value_at<uint16_t>(typed + 2 * i);
    case NrrdType::kFloat32:
      return value_at<float>(typed + 4 * i);
    case NrrdType::kFloat64:
      return value_at<double>(typed + 8 * i);
  }
  return 0.0;
}

}  // namespace

Status NrrdReader::read_density_slices(int slices, const DensityWindow* window,
                                       std::span<uint8_t> out) {
  Impl& s = *impl_;
  const NrrdType type = s.header.type;
  if (window == nullptr) {
    if (type != NrrdType::kUInt8) {
      return s.fail(std::string("holds ") + nrrd_type_name(type) +
                    " voxels: map them to density with --window LO,HI or --data-iso V");
    }
    return read_slices(slices, std::as_writable_bytes(out));
  }
  s.typed.resize(out.size() * nrrd_type_size(type));
  if (Status st = read_slices(slices, s.typed); !st) return st;
  const double lo = window->lo, scale = 255.0 / (window->hi - window->lo);
  for (size_t i = 0; i < out.size(); ++i) {
    const double v = typed_value(type, s.typed.data(), i);
    if (!std::isfinite(v)) return s.fail("a voxel value is not a finite number");
    out[i] = static_cast<uint8_t>(std::clamp(std::round((v - lo) * scale), 0.0, 255.0));
  }
  return {};
}

Result<DensityWindow> window_around(const std::filesystem::path& path, double iso,
                                    const NrrdLimits& limits) {
  auto reader = NrrdReader::open(path, limits);
  if (!reader) return reader.error();
  const NrrdHeader& h = reader->header();
  const size_t slice = static_cast<size_t>(h.dims.x) * static_cast<size_t>(h.dims.y);
  std::vector<std::byte> typed(slice * nrrd_type_size(h.type));
  double lo = iso, hi = iso;
  for (int z = 0; z < h.dims.z; ++z) {
    if (Status st = reader->read_slices(1, typed); !st) return st.error();
    for (size_t i = 0; i < slice; ++i) {
      const double v = typed_value(h.type, typed.data(), i);
      if (!std::isfinite(v)) return Error(path.string() + ": a voxel value is not a finite number");
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  const double half = std::max({iso - lo, hi - iso, 1e-6 * std::max(1.0, std::fabs(iso))});
  return DensityWindow{iso - half, iso + half};
}

Result<DenseGrid<uint8_t>> read_nrrd_density(const std::filesystem::path& path,
                                             const DensityWindow* window,
                                             const NrrdLimits& limits) {
  auto reader = NrrdReader::open(path, limits);
  if (!reader) return reader.error();
  const NrrdHeader& h = reader->header();
  // A slab at a time, so data that ends early stops the read before the
  // declared size is reserved.
  std::vector<uint8_t> values;
  const size_t slice = static_cast<size_t>(h.dims.x) * static_cast<size_t>(h.dims.y);
  const int slab = static_cast<int>(std::max<size_t>(1, (size_t{64} << 20) / slice));
  for (int z = 0; z < h.dims.z; z += slab) {
    const int n = std::min(slab, h.dims.z - z);
    const size_t at = values.size();
    values.resize(at + slice * static_cast<size_t>(n));
    if (Status st = reader->read_density_slices(n, window, std::span(values).subspan(at)); !st)
      return st.error();
  }
  DenseGrid<uint8_t> grid(h.dims);
  grid.values() = std::move(values);
  return grid;
}

namespace {

// A double volume as float (distance fields written by other tools).
Result<DenseGrid<float>> read_doubles(NrrdReader& reader) {
  const NrrdHeader& h = reader.header();
  const size_t slice = static_cast<size_t>(h.dims.x) * static_cast<size_t>(h.dims.y);
  std::vector<double> doubles(slice);
  std::vector<float> values;
  for (int z = 0; z < h.dims.z; ++z) {
    if (Status st = reader.read_slices(1, std::as_writable_bytes(std::span(doubles))); !st)
      return st.error();
    for (double d : doubles)
      values.push_back(static_cast<float>(d));
  }
  DenseGrid<float> grid(h.dims);
  grid.values() = std::move(values);
  return grid;
}

template <class T>
Result<DenseGrid<T>> read_whole(const std::filesystem::path& path, const NrrdLimits& limits,
                                NrrdType want) {
  auto reader = NrrdReader::open(path, limits);
  if (!reader) return reader.error();
  const NrrdHeader& h = reader->header();
  if constexpr (std::is_same_v<T, float>) {
    if (h.type == NrrdType::kFloat64) return read_doubles(*reader);
  }
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

// Our own reader refuses a float volume with NaN or an infinity, and so do
// most tools downstream: such a volume is a bug upstream, named here rather
// than written.
Status check_finite(const std::filesystem::path& path, const DenseGrid<float>& grid) {
  const auto bad = std::find_if(grid.values().begin(), grid.values().end(),
                                [](float v) { return !std::isfinite(v); });
  if (bad == grid.values().end()) return {};
  const auto i = static_cast<int64_t>(bad - grid.values().begin());
  const glm::ivec3 d = grid.dims();
  const int64_t x = i % d.x, y = i / d.x % d.y, z = i / (int64_t{d.x} * d.y);
  return Error(path.string() + ": voxel (" + std::to_string(x) + ", " + std::to_string(y) + ", " +
               std::to_string(z) + ") is " + (std::isnan(*bad) ? "NaN" : "infinite") +
               ", not a finite number; nothing written");
}
Status check_finite(const std::filesystem::path&, const DenseGrid<uint8_t>&) {
  return {};
}

template <class T>
Status write_whole(const std::filesystem::path& path, const DenseGrid<T>& grid, NrrdType type) {
  if (Status finite = check_finite(path, grid); !finite) return finite;
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
