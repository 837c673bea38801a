#include "sculpt/core/io/nrrd.h"

#include <gtest/gtest.h>

#include <bzlib.h>
#include <zlib.h>
#include "scratch_dir.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

namespace sculpt::core {
namespace {

namespace fs = std::filesystem;

class NrrdTest : public ::testing::Test {
 protected:
  fs::path write_file(const std::string& name, const std::string& bytes) {
    const fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
  }
  // Expects the read to fail with a message naming the file and containing `what`.
  void expect_refused(const fs::path& p, const std::string& what) {
    const auto r = read_nrrd_u8(p);
    ASSERT_FALSE(r.ok()) << p;
    EXPECT_NE(r.error().message().find(p.string()), std::string::npos) << r.error().message();
    EXPECT_NE(r.error().message().find(what), std::string::npos)
        << r.error().message() << " (wanted: " << what << ")";
    EXPECT_EQ(r.error().message().find('\n'), std::string::npos) << "one line";
  }
  sculpt::test::ScratchDir scratch_;
  const fs::path& dir_ = scratch_.path();
};

std::string gzip(const std::string& data) {
  z_stream zs{};
  EXPECT_EQ(deflateInit2(&zs, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY), Z_OK);
  std::string out(deflateBound(&zs, static_cast<uLong>(data.size())) + 32, '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  zs.avail_in = static_cast<uInt>(data.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&zs, Z_FINISH), Z_STREAM_END);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

std::string bytes_of(const DenseGrid<uint8_t>& g) {
  return {reinterpret_cast<const char*>(g.data()), g.size()};
}

DenseGrid<uint8_t> ramp(glm::ivec3 dims) {
  DenseGrid<uint8_t> g(dims);
  for (size_t i = 0; i < g.size(); ++i)
    g[i] = static_cast<uint8_t>(i * 7 + 3);
  return g;
}

TEST_F(NrrdTest, Uint8RoundTripIsExact) {
  const DenseGrid<uint8_t> g = ramp({7, 5, 3});
  ASSERT_TRUE(write_nrrd(dir_ / "a.nrrd", g).ok());
  const auto r = read_nrrd_u8(dir_ / "a.nrrd");
  ASSERT_TRUE(r.ok()) << r.error().message();
  EXPECT_EQ(*r, g);
}

TEST_F(NrrdTest, Float32RoundTripIsExact) {
  DenseGrid<float> g({4, 3, 2});
  for (size_t i = 0; i < g.size(); ++i)
    g[i] = -1.5f + 0.25f * static_cast<float>(i);
  ASSERT_TRUE(write_nrrd(dir_ / "d.nrrd", g).ok());
  const auto r = read_nrrd_f32(dir_ / "d.nrrd");
  ASSERT_TRUE(r.ok()) << r.error().message();
  EXPECT_EQ(*r, g);
  // The wrong type is refused, naming what the file holds.
  const auto wrong = read_nrrd_u8(dir_ / "d.nrrd");
  ASSERT_FALSE(wrong.ok());
  EXPECT_NE(wrong.error().message().find("holds float"), std::string::npos);
}

TEST_F(NrrdTest, ReadsGzipBigEndianCommentsAndKeyValues) {
  DenseGrid<float> g({3, 2, 2});
  std::string raw;
  for (size_t i = 0; i < g.size(); ++i) {
    g[i] = static_cast<float>(i) - 4.0f;
    uint32_t bits;
    std::memcpy(&bits, &g[i], 4);
    for (int s = 24; s >= 0; s -= 8)
      raw.push_back(static_cast<char>(bits >> s));  // big endian
  }
  const std::string header =
      "NRRD0005\n# a comment\ntype: float\ndimension: 3\nspace: left-posterior-superior\n"
      "sizes: 3 2 2\nspace directions: (1,0,0) (0,1,0) (0,0,1)\nendian: big\nencoding: gzip\n"
      "sculpt_pivot:=1 2 3\n\n";
  const auto r = read_nrrd_f32(write_file("g.nrrd", header + gzip(raw)));
  ASSERT_TRUE(r.ok()) << r.error().message();
  EXPECT_EQ(*r, g);
}

TEST_F(NrrdTest, ReadsDetachedData) {
  const DenseGrid<uint8_t> g = ramp({4, 4, 4});
  write_file("data.raw", bytes_of(g));
  const auto r = read_nrrd_u8(write_file(
      "h.nhdr",
      "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 4 4 4\nencoding: raw\ndata file: data.raw\n"));
  ASSERT_TRUE(r.ok()) << r.error().message();
  EXPECT_EQ(*r, g);
}

TEST_F(NrrdTest, StreamsSlices) {
  const DenseGrid<uint8_t> g = ramp({5, 4, 6});
  ASSERT_TRUE(write_nrrd(dir_ / "s.nrrd", g).ok());
  auto reader = NrrdReader::open(dir_ / "s.nrrd");
  ASSERT_TRUE(reader.ok());
  std::vector<std::byte> slab(5 * 4 * 2);
  for (int z = 0; z < 6; z += 2) {
    ASSERT_TRUE(reader->read_slices(2, slab).ok());
    EXPECT_EQ(std::memcmp(slab.data(), &g.at(0, 0, z), slab.size()), 0);
  }
}

TEST_F(NrrdTest, RefusesMalformedHeaders) {
  const std::string data(8, 'x');
  expect_refused(write_file("magic.nrrd", "P6\n2 2\n255\n" + data), "not a NRRD file");
  expect_refused(write_file("empty.nrrd", ""), "not a NRRD file");
  expect_refused(
      write_file("notype.nrrd", "NRRD0004\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\n" + data),
      "missing required field 'type'");
  expect_refused(
      write_file("dim.nrrd",
                 "NRRD0004\ntype: uint8\ndimension: 2\nsizes: 2 4\nencoding: raw\n\n" + data),
      "dimension 2 is not supported");
  expect_refused(
      write_file("type.nrrd",
                 "NRRD0004\ntype: int64\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\n" + data),
      "type 'int64' is not supported");
  expect_refused(
      write_file("sizes.nrrd",
                 "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2\nencoding: raw\n\n" + data),
      "expected 3 numbers, got 2");
  expect_refused(
      write_file("neg.nrrd",
                 "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 -2 2\nencoding: raw\n\n" + data),
      "'-2' is not a positive integer");
  expect_refused(
      write_file("enc.nrrd",
                 "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: zrl\n\n" + data),
      "encoding 'zrl' is not supported");
  expect_refused(
      write_file("endian.nrrd",
                 "NRRD0004\ntype: float\ndimension: 3\nsizes: 1 1 2\nencoding: raw\n\n" + data),
      "missing required field 'endian'");
  expect_refused(
      write_file(
          "twice.nrrd",
          "NRRD0004\ntype: uint8\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\n" +
              data),
      "appears twice");
  expect_refused(write_file("line.nrrd", "NRRD0004\ntype uint8\n\n" + data),
                 "is not 'field: value'");
  expect_refused(
      write_file("noend.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw"),
      "blank line");
  expect_refused(dir_ / "missing.nrrd", "cannot open");
}

TEST_F(NrrdTest, RefusesAbsurdSizesBeforeAllocating) {
  // 10^15 voxels with 8 bytes of data: refused from the header alone.
  expect_refused(write_file("huge.nrrd",
                            "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 100000 100000 100000\n"
                            "encoding: gzip\n\n" +
                                gzip("12345678")),
                 "too large");
  expect_refused(write_file("overflow.nrrd",
                            "NRRD0004\ntype: uint8\ndimension: 3\n"
                            "sizes: 99999999999999999999 1 1\nencoding: raw\n\n"),
                 "is not a positive integer");
}

TEST_F(NrrdTest, RefusesTruncatedAndOverlongData) {
  const std::string header = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n\n";
  expect_refused(write_file("short.nrrd", header + std::string(63, 'a')), "truncated data");
  expect_refused(write_file("long.nrrd", header + std::string(65, 'a')), "1 bytes more data");
  const std::string gz = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 4 4 4\nencoding: gzip\n\n";
  expect_refused(write_file("gzshort.nrrd", gz + gzip(std::string(60, 'a'))),
                 "truncated gzip data");
  expect_refused(write_file("gzlong.nrrd", gz + gzip(std::string(70, 'a'))),
                 "longer than the sizes say");
  std::string cut = gzip(std::string(64, 'a'));
  cut.resize(cut.size() / 2);
  expect_refused(write_file("gzcut.nrrd", gz + cut), "truncated gzip data");
  expect_refused(write_file("gzjunk.nrrd", gz + std::string(40, '\x55')), "corrupt gzip data");
  // Bytes after a complete stream (a second stream, or junk) are refused.
  expect_refused(write_file("gztail.nrrd", gz + gzip(std::string(64, 'a')) + "junk"),
                 "bytes follow the gzip data");
  expect_refused(
      write_file("gztwo.nrrd", gz + gzip(std::string(64, 'a')) + gzip(std::string(64, 'b'))),
      "bytes follow the gzip data");
  // A large claimed size with little gzip data fails on the data, not on memory.
  expect_refused(write_file("gzlie.nrrd",
                            "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 1000 1000 1000\n"
                            "encoding: gzip\n\n" +
                                gzip("abc")),
                 "truncated gzip data");
}

std::string bzip2(const std::string& data) {
  std::string out(data.size() + data.size() / 100 + 600, '\0');
  unsigned size = static_cast<unsigned>(out.size());
  EXPECT_EQ(BZ2_bzBuffToBuffCompress(out.data(), &size, const_cast<char*>(data.data()),
                                     static_cast<unsigned>(data.size()), 9, 0, 0),
            BZ_OK);
  out.resize(size);
  return out;
}

std::string header(const char* type, const char* encoding, const char* endian = nullptr) {
  std::string h = std::string("NRRD0005\ntype: ") + type + "\ndimension: 3\nsizes: 3 2 2\n";
  if (endian != nullptr) h += std::string("endian: ") + endian + "\n";
  return h + "encoding: " + encoding + "\n\n";
}

// CT-like 16-bit values (Hounsfield units), x fastest.
const int16_t kCt[12] = {-1000, -500, 0, 100, 300, 400, 500, 1000, 2000, 3000, -1024, 3071};

std::string big_endian_int16(const int16_t* v, int n) {
  std::string b;
  for (int i = 0; i < n; ++i) {
    b.push_back(static_cast<char>(static_cast<uint16_t>(v[i]) >> 8));
    b.push_back(static_cast<char>(static_cast<uint16_t>(v[i]) & 0xff));
  }
  return b;
}

// The encodings and types teem writes (nrrd format spec, "encoding" and
// "type"): the same 16-bit volume through each encoding reads back equal.
TEST_F(NrrdTest, ReadsEveryEncodingAndSixteenBitAndDoubleVoxels) {
  const std::string raw = big_endian_int16(kCt, 12);
  std::string hex;
  for (size_t i = 0; i < raw.size(); ++i) {
    char d[3];
    std::snprintf(d, sizeof d, "%02x", static_cast<unsigned char>(raw[i]));
    hex += d;
    hex += i % 8 == 7 ? "\n" : "";
  }
  std::string ascii;
  for (int16_t v : kCt)
    ascii += std::to_string(v) + (v == 3071 ? "\n" : " ");
  const fs::path files[] = {
      write_file("raw.nrrd", header("short", "raw", "big") + raw),
      write_file("gz.nrrd", header("signed short", "gzip", "big") + gzip(raw)),
      write_file("bz.nrrd", header("int16", "bzip2", "big") + bzip2(raw)),
      write_file("hex.nrrd", header("int16_t", "hex", "big") + hex),
      write_file("txt.nrrd", header("short int", "ascii") + ascii),
  };
  const DensityWindow window{-1000.0, 1000.0};
  for (const fs::path& f : files) {
    const auto d = read_nrrd_density(f, &window);
    ASSERT_TRUE(d.ok()) << f << ": " << d.error().message();
    for (int i = 0; i < 12; ++i) {
      const double expected =
          std::clamp(std::round((kCt[i] + 1000.0) * 255.0 / 2000.0), 0.0, 255.0);
      EXPECT_EQ(d->values()[size_t(i)], expected) << f << " voxel " << i;
    }
  }
  // Without a mapping, 16-bit data is refused naming the options that map it.
  const auto unmapped = read_nrrd_density(files[0], nullptr);
  ASSERT_FALSE(unmapped.ok());
  EXPECT_NE(
      unmapped.error().message().find("holds int16 voxels: map them to density with --window"),
      std::string::npos)
      << unmapped.error().message();
  // uint16 and double, little endian.
  std::string u16, f64;
  for (int i = 0; i < 12; ++i) {
    const uint16_t u = static_cast<uint16_t>(i * 5000);
    u16.append(reinterpret_cast<const char*>(&u), 2);
    const double v = -2.5 + i * 0.75;
    f64.append(reinterpret_cast<const char*>(&v), 8);
  }
  const auto wide =
      read_nrrd_density(write_file("u16.nrrd", header("ushort", "raw", "little") + u16), &window);
  ASSERT_TRUE(wide.ok()) << wide.error().message();
  EXPECT_EQ(wide->values()[1], 255);  // 5000 is above the window
  const auto doubles =
      read_nrrd_f32(write_file("f64.nrrd", header("double", "gzip", "little") + gzip(f64)));
  ASSERT_TRUE(doubles.ok()) << doubles.error().message();
  EXPECT_EQ(doubles->values()[3], -0.25f);
}

TEST_F(NrrdTest, DataIsoTakesTheNarrowestWindowHoldingAllValues) {
  const fs::path f =
      write_file("ct.nrrd", header("short", "raw", "big") + big_endian_int16(kCt, 12));
  const auto window = window_around(f, 400.0);
  ASSERT_TRUE(window.ok()) << window.error().message();
  EXPECT_EQ(window->lo, 400.0 - 2671.0);  // 3071 is the farthest value from 400
  EXPECT_EQ(window->hi, 400.0 + 2671.0);
  const auto d = read_nrrd_density(f, &*window);
  ASSERT_TRUE(d.ok());
  EXPECT_EQ(d->values()[5], 128);  // 400 sits in the middle: round(127.5)
  EXPECT_EQ(d->values()[11], 255);
}

TEST_F(NrrdTest, RefusesBadTextAndCompressedDataNamingTheFile) {
  const struct {
    const char* name;
    std::string bytes;
    const char* what;
  } cases[] = {
      {"word.nrrd", header("short", "ascii") + "1 2 3 4 5 x6 7 8 9 10 11 12\n",
       "ascii data: 'x6' is not a int16"},
      {"range.nrrd", header("short", "ascii") + "1 2 3 4 5 40000 7 8 9 10 11 12\n",
       "'40000' is not a int16"},
      {"nan.nrrd", header("double", "ascii") + "1 2 3 4 5 nan 7 8 9 10 11 12\n",
       "'nan' is not a finite number"},
      {"long.nrrd", header("short", "ascii") + "1 2 3 4 5 6 7 8 9 10 11 12 13\n",
       "ascii data is longer than the sizes say"},
      {"short.nrrd", header("short", "ascii") + "1 2 3\n", "truncated data"},
      {"hex.nrrd", header("uint8", "hex") + "00 11 22 33 44 5g 66 77 88 99 aa bb\n",
       "hex data: 'g' is not a hex digit"},
      {"bz.nrrd", header("uint8", "bzip2") + bzip2(std::string(12, 'a')) + "junk",
       "bytes follow the bzip2 data"},
      {"bzcut.nrrd", header("uint8", "bzip2") + bzip2(std::string(12, 'a')).substr(0, 20),
       "truncated bzip2 data"},
      {"bzshort.nrrd", header("uint8", "bzip2") + bzip2(std::string(11, 'a')),
       "truncated bzip2 data"},
  };
  for (const auto& c : cases) {
    const fs::path f = write_file(c.name, c.bytes);
    const DensityWindow window{0.0, 255.0};
    const auto mapped = read_nrrd_density(f, &window);
    ASSERT_FALSE(mapped.ok()) << c.name;
    EXPECT_NE(mapped.error().message().find(f.string()), std::string::npos)
        << mapped.error().message();
    EXPECT_NE(mapped.error().message().find(c.what), std::string::npos)
        << c.name << ": " << mapped.error().message();
  }
}

TEST_F(NrrdTest, FailedWriteLeavesNoFile) {
  const fs::path target = dir_ / "no_such_folder" / "out.nrrd";
  const Status st = write_nrrd(target, ramp({2, 2, 2}));
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().message().find(target.string()), std::string::npos);
  EXPECT_FALSE(fs::exists(target));
}

TEST_F(NrrdTest, RefusesToWriteNonFiniteVoxelsNamingTheFirst) {
  for (float bad : {std::nanf(""), std::numeric_limits<float>::infinity()}) {
    DenseGrid<float> field({3, 4, 5}, 1.5f);
    field.at(2, 1, 3) = bad;
    const fs::path target = dir_ / "field.nrrd";
    const Status st = write_nrrd(target, field);
    ASSERT_FALSE(st.ok());
    EXPECT_NE(st.error().message().find(target.string()), std::string::npos);
    EXPECT_NE(st.error().message().find("voxel (2, 1, 3)"), std::string::npos)
        << st.error().message();
    EXPECT_FALSE(fs::exists(target));
  }
}

}  // namespace
}  // namespace sculpt::core
