#include "io/nrrd_sources.h"

#include <bzlib.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace sculpt::core::detail {
namespace {

constexpr size_t kInputChunk = size_t{1} << 16;

class RawSource final : public NrrdSource {
 public:
  explicit RawSource(std::FILE* file) : file_(file) {}
  Status read(std::span<std::byte> out) override {
    if (std::fread(out.data(), 1, out.size(), file_) != out.size())
      return Error("truncated data (unexpected end of file)");
    return {};
  }
  // The length was checked against the sizes when the file was opened.
  Status finish() override { return {}; }

 private:
  std::FILE* file_;
};

// What gzip and bzip2 share: compressed input read in chunks, a stream that
// must end exactly where the sizes say, and nothing after it.
class CompressedSource : public NrrdSource {
 public:
  explicit CompressedSource(std::FILE* file) : file_(file), input_(kInputChunk) {}

  Status read(std::span<std::byte> out) override {
    size_t done = 0;
    while (done < out.size()) {
      if (ended_)
        return Error(std::string("truncated ") + name() +
                     " data (the stream ends before the sizes say)");
      if (available_ == 0) refill();
      const size_t want = std::min<size_t>(out.size() - done, size_t{1} << 30);
      size_t produced = 0;
      if (Status st = step(out.data() + done, want, produced); !st) return st;
      done += produced;
      // No input left and the decoder had nothing more buffered.
      if (produced == 0 && !ended_ && available_ == 0 && at_end_of_file_)
        return Error(std::string("truncated ") + name() + " data (unexpected end of file)");
    }
    return {};
  }

  Status finish() override {
    if (!ended_) {
      // The stream must end now: one more byte out means the sizes are short.
      std::byte extra;
      for (;;) {
        if (available_ == 0) refill();
        size_t produced = 0;
        if (Status st = step(&extra, 1, produced); !st) return st;
        if (produced > 0)
          return Error(std::string(name()) +
                       " data is longer than the sizes say (wrong sizes or type?)");
        if (ended_) break;
        if (available_ == 0 && at_end_of_file_)
          return Error(std::string("truncated ") + name() + " data (the stream has no end)");
      }
    }
    // Bytes after the stream are a second stream or a damaged file, and
    // ignoring them would read a different volume.
    char more;
    if (available_ > 0 || std::fread(&more, 1, 1, file_) == 1)
      return Error(std::string("bytes follow the ") + name() +
                   " data (a damaged or concatenated file)");
    return {};
  }

 protected:
  // Decompresses into out[0, want) from the available input; sets ended_ at
  // the stream's end and `produced` to the bytes written.
  virtual Status step(std::byte* out, size_t want, size_t& produced) = 0;
  virtual const char* name() const = 0;

  void refill() {
    available_ = std::fread(input_.data(), 1, input_.size(), file_);
    next_ = input_.data();
    at_end_of_file_ = available_ == 0;
  }

  std::FILE* file_;
  std::vector<unsigned char> input_;
  unsigned char* next_ = nullptr;
  size_t available_ = 0;
  bool at_end_of_file_ = false;
  bool ended_ = false;
};

class GzipSource final : public CompressedSource {
 public:
  explicit GzipSource(std::FILE* file) : CompressedSource(file) {
    ok_ = inflateInit2(&z_, 15 + 32) == Z_OK;  // gzip or zlib header
  }
  ~GzipSource() override {
    if (ok_) inflateEnd(&z_);
  }

 protected:
  const char* name() const override { return "gzip"; }
  Status step(std::byte* out, size_t want, size_t& produced) override {
    if (!ok_) return Error("cannot start gzip decoding");
    z_.next_in = next_;
    z_.avail_in = static_cast<uInt>(available_);
    z_.next_out = reinterpret_cast<Bytef*>(out);
    z_.avail_out = static_cast<uInt>(want);
    const int rc = inflate(&z_, Z_NO_FLUSH);
    produced = want - z_.avail_out;
    next_ = z_.next_in;
    available_ = z_.avail_in;
    if (rc == Z_STREAM_END) {
      ended_ = true;
    } else if (rc != Z_OK && rc != Z_BUF_ERROR) {
      return Error(std::string("corrupt gzip data (zlib: ") + (z_.msg ? z_.msg : "error") + ")");
    }
    return {};
  }

 private:
  z_stream z_{};
  bool ok_ = false;
};

class Bzip2Source final : public CompressedSource {
 public:
  explicit Bzip2Source(std::FILE* file) : CompressedSource(file) {
    ok_ = BZ2_bzDecompressInit(&bz_, 0, 0) == BZ_OK;
  }
  ~Bzip2Source() override {
    if (ok_) BZ2_bzDecompressEnd(&bz_);
  }

 protected:
  const char* name() const override { return "bzip2"; }
  Status step(std::byte* out, size_t want, size_t& produced) override {
    if (!ok_) return Error("cannot start bzip2 decoding");
    bz_.next_in = reinterpret_cast<char*>(next_);
    bz_.avail_in = static_cast<unsigned>(available_);
    bz_.next_out = reinterpret_cast<char*>(out);
    bz_.avail_out = static_cast<unsigned>(want);
    const int rc = BZ2_bzDecompress(&bz_);
    produced = want - bz_.avail_out;
    next_ = reinterpret_cast<unsigned char*>(bz_.next_in);
    available_ = bz_.avail_in;
    if (rc == BZ_STREAM_END) {
      ended_ = true;
    } else if (rc != BZ_OK) {
      return Error("corrupt bzip2 data (libbz2 error " + std::to_string(rc) + ")");
    }
    return {};
  }

 private:
  bz_stream bz_{};
  bool ok_ = false;
};

// Characters of the text encodings, read through a buffer.
class TextInput {
 public:
  explicit TextInput(std::FILE* file) : file_(file), buffer_(kInputChunk) {}
  /// The next character, or EOF.
  int get() {
    if (at_ == size_) {
      size_ = std::fread(buffer_.data(), 1, buffer_.size(), file_);
      at_ = 0;
      if (size_ == 0) return EOF;
    }
    return static_cast<unsigned char>(buffer_[at_++]);
  }
  /// The next character that is not whitespace, or EOF.
  int get_visible() {
    int c;
    do {
      c = get();
    } while (c != EOF && std::isspace(c));
    return c;
  }

 private:
  std::FILE* file_;
  std::vector<char> buffer_;
  size_t at_ = 0, size_ = 0;
};

std::string printable(int c) {
  if (c >= 0x20 && c < 0x7f) return std::string(1, static_cast<char>(c));
  char text[8];
  std::snprintf(text, sizeof text, "\\x%02X", c & 0xff);
  return text;
}

// Two hex digits per byte, whitespace anywhere between them (teem writes
// lines of 32 digits).
class HexSource final : public NrrdSource {
 public:
  explicit HexSource(std::FILE* file) : in_(file) {}
  Status read(std::span<std::byte> out) override {
    for (std::byte& b : out) {
      int value = 0;
      for (int half = 0; half < 2; ++half) {
        const int c = in_.get_visible();
        if (c == EOF) return Error("truncated hex data (unexpected end of file)");
        if (!std::isxdigit(c)) return Error("hex data: '" + printable(c) + "' is not a hex digit");
        value = value * 16 + (std::isdigit(c) ? c - '0' : std::tolower(c) - 'a' + 10);
      }
      b = static_cast<std::byte>(value);
    }
    return {};
  }
  Status finish() override {
    if (in_.get_visible() != EOF)
      return Error("hex data is longer than the sizes say (wrong sizes or type?)");
    return {};
  }

 private:
  TextInput in_;
};

// Numbers separated by whitespace, one per value, written in host order.
class AsciiSource final : public NrrdSource {
 public:
  AsciiSource(std::FILE* file, NrrdType type) : in_(file), type_(type) {}
  Status read(std::span<std::byte> out) override {
    const size_t size = nrrd_type_size(type_);
    for (size_t at = 0; at < out.size(); at += size) {
      std::string token;
      int c = in_.get_visible();
      while (c != EOF && !std::isspace(c)) {
        if (token.size() > 64) return Error("ascii data: a number longer than 64 characters");
        token.push_back(static_cast<char>(c));
        c = in_.get();
      }
      if (token.empty()) return Error("truncated ascii data (unexpected end of file)");
      if (Status st = convert(token, out.data() + at); !st) return st;
    }
    return {};
  }
  Status finish() override {
    if (in_.get_visible() != EOF)
      return Error("ascii data is longer than the sizes say (wrong sizes or type?)");
    return {};
  }

 private:
  template <class T>
  static Status whole(const std::string& token, std::byte* out) {
    int64_t v = 0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
    if (ec != std::errc() || end != token.data() + token.size() ||
        v < std::numeric_limits<T>::min() || v > std::numeric_limits<T>::max()) {
      return Error("ascii data: '" + token.substr(0, 32) + "' is not a " + type_word<T>());
    }
    const T t = static_cast<T>(v);
    std::memcpy(out, &t, sizeof t);
    return {};
  }
  template <class T>
  static const char* type_word() {
    if constexpr (std::is_same_v<T, uint8_t>) return "uint8";
    if constexpr (std::is_same_v<T, int16_t>) return "int16";
    return "uint16";
  }
  template <class T>
  static Status real(const std::string& token, std::byte* out) {
    char* end = nullptr;
    const double v = std::strtod(token.c_str(), &end);
    if (end != token.c_str() + token.size() || !std::isfinite(v) ||
        std::fabs(v) > double(std::numeric_limits<T>::max())) {
      return Error("ascii data: '" + token.substr(0, 32) + "' is not a finite number");
    }
    const T t = static_cast<T>(v);
    std::memcpy(out, &t, sizeof t);
    return {};
  }
  Status convert(const std::string& token, std::byte* out) const {
    switch (type_) {
      case NrrdType::kUInt8:
        return whole<uint8_t>(token, out);
      case NrrdType::kInt16:
        return whole<int16_t>(token, out);
      case NrrdType::kUInt16:
        return whole<uint16_t>(token, out);
      case NrrdType::kFloat32:
        return real<float>(token, out);
      case NrrdType::kFloat64:
        return real<double>(token, out);
    }
    return Error("ascii data: unknown type");
  }

  TextInput in_;
  NrrdType type_;
};

}  // namespace

std::unique_ptr<NrrdSource> make_nrrd_source(NrrdEncoding encoding, NrrdType type,
                                             std::FILE* file) {
  switch (encoding) {
    case NrrdEncoding::kRaw:
      return std::make_unique<RawSource>(file);
    case NrrdEncoding::kGzip:
      return std::make_unique<GzipSource>(file);
    case NrrdEncoding::kBzip2:
      return std::make_unique<Bzip2Source>(file);
    case NrrdEncoding::kHex:
      return std::make_unique<HexSource>(file);
    case NrrdEncoding::kAscii:
      return std::make_unique<AsciiSource>(file, type);
  }
  return nullptr;
}

}  // namespace sculpt::core::detail
