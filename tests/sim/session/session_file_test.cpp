#include "sculpt/sim/session/session_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "sculpt/sim/synth/bundled_sessions.h"

namespace sculpt::sim {
namespace {

namespace fs = std::filesystem;

Session small_session() {
  Session s;
  s.header.device.backend = "hidapi";
  s.header.device.path = "/dev/hidraw3";
  s.header.device.name = "SpaceMouse Compact";
  s.header.device.vendor_id = 0x256f;
  s.header.device.product_id = 0xc635;
  s.header.device.usage_page = 1;
  s.header.device.usage = 8;
  s.header.device.report_descriptor = {0x05, 0x01, 0x09, 0x08};
  s.header.normalizer_config = "deadzone = 0.1\n";
  s.header.created_unix_ns = 1234567890123;
  const uint8_t motion[13] = {1, 10, 0, 246, 255, 0, 0, 1, 0, 2, 0, 3, 0};
  s.records.push_back(SessionRecord::of(hal::RawEvent::report(1000, motion)));
  Command tool{CommandKind::kTool, static_cast<uint8_t>(ToolShape::kRing)};
  tool.values[0] = 12.5f;
  tool.values[1] = 0.1f;
  s.records.push_back(SessionRecord::of(1000, tool));
  s.records.push_back(SessionRecord::of(hal::RawEvent::axis(2000, 4, -350)));
  s.records.push_back(SessionRecord::of(hal::RawEvent::button(2500, 1, true)));
  s.records.push_back(SessionRecord::of(hal::RawEvent::sync(3000)));
  hal::RawEvent long_report = hal::RawEvent::report(3500, motion);
  long_report.truncated = true;
  s.records.push_back(SessionRecord::of(long_report));
  s.records.push_back(SessionRecord::of(hal::RawEvent::removed(4000)));
  return s;
}

TEST(SessionFile, RoundTripIsExact) {
  const Session s = small_session();
  SessionReadInfo info;
  const auto back = parse_session_bytes(serialize_session(s), "mem", &info);
  ASSERT_TRUE(back.ok()) << back.error().message();
  EXPECT_EQ(*back, s);
  EXPECT_EQ(info.records, 7);
  EXPECT_EQ(info.bytes_lost, 0);
  EXPECT_TRUE(info.warning.empty());
}

// Cut anywhere: the header is refused, a record is dropped with everything
// after it, and the loss is reported. Never a crash.
TEST(SessionFile, EveryTruncationKeepsTheWholeRecordsBeforeIt) {
  const Session s = small_session();
  const std::vector<uint8_t> bytes = serialize_session(s);
  const size_t header_end = serialize_session(Session{s.header, {}}).size();
  for (size_t n = 0; n < bytes.size(); ++n) {
    SessionReadInfo info;
    const auto r = parse_session_bytes({bytes.data(), n}, "cut.scs", &info);
    if (n < header_end) {
      ASSERT_FALSE(r.ok()) << n;
      EXPECT_NE(r.error().message().find("cut.scs: "), std::string::npos);
      continue;
    }
    ASSERT_TRUE(r.ok()) << n;
    ASSERT_LE(r->records.size(), s.records.size());
    for (size_t i = 0; i < r->records.size(); ++i)
      EXPECT_EQ(r->records[i], s.records[i]);
    EXPECT_EQ(info.bytes_lost == 0, info.warning.empty());
    if (info.bytes_lost > 0) {
      EXPECT_NE(info.warning.find("bytes lost"), std::string::npos);
    }
  }
}

TEST(SessionFile, RefusesForeignAndDamagedHeaders) {
  std::vector<uint8_t> bytes = serialize_session(small_session());
  auto refused = [](std::vector<uint8_t> b, const std::string& what) {
    const auto r = parse_session_bytes(b, "x.scs");
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message().find(what), std::string::npos) << r.error().message();
  };
  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0};
  refused(png, "bad magic");
  std::vector<uint8_t> version = bytes;
  version[8] = 7;
  refused(version, "session version 7 is not supported");
  std::vector<uint8_t> header = bytes;
  header[20] ^= 0xff;
  refused(header, "header checksum mismatch");
  std::vector<uint8_t> absurd = bytes;
  absurd[12] = absurd[13] = absurd[14] = absurd[15] = 0xff;
  refused(absurd, "is absurd");
}

TEST(SessionFile, DamagedRecordTruncatesThereAndSaysSo) {
  const Session s = small_session();
  std::vector<uint8_t> bytes = serialize_session(s);
  bytes[bytes.size() - 30] ^= 0x40;  // inside one of the last records
  SessionReadInfo info;
  const auto r = parse_session_bytes(bytes, "d.scs", &info);
  ASSERT_TRUE(r.ok());
  EXPECT_LT(r->records.size(), s.records.size());
  EXPECT_GT(info.bytes_lost, 0);
  EXPECT_NE(info.warning.find("d.scs: checksum mismatch in record"), std::string::npos)
      << info.warning;
}

TEST(SessionFile, WriterAppendsAndACrashLosesNothingWritten) {
  const fs::path p =
      fs::temp_directory_path() / ("sculpt_writer_" + std::to_string(::getpid()) + ".scs");
  const Session s = small_session();
  {
    auto w = SessionWriter::create(p, s.header);
    ASSERT_TRUE(w.ok()) << w.error().message();
    for (size_t i = 0; i < 4; ++i)
      ASSERT_TRUE(w->append(s.records[i]).ok());
    // No close: read what a crash at this point would leave on disk.
    SessionReadInfo info;
    const auto mid = read_session_file(p, &info);
    ASSERT_TRUE(mid.ok());
    EXPECT_EQ(mid->records.size(), 4u);
    EXPECT_EQ(info.bytes_lost, 0);
    EXPECT_FALSE(w->append(SessionRecord::of(hal::RawEvent::sync(0))).ok());  // back in time
    for (size_t i = 4; i < s.records.size(); ++i)
      ASSERT_TRUE(w->append(s.records[i]).ok());
    ASSERT_TRUE(w->close().ok());
  }
  const auto back = read_session_file(p);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(*back, s);
  fs::remove(p);
}

TEST(SessionFile, WritersRefuseACommandTheReadersWouldRefuse) {
  const fs::path p =
      fs::temp_directory_path() / ("sculpt_bad_command_" + std::to_string(::getpid()) + ".scs");
  Session s = small_session();
  Command nan_strength{CommandKind::kStrength};
  nan_strength.values[0] = std::nanf("");
  s.records.insert(s.records.begin() + 2, SessionRecord::of(1500, nan_strength));
  const Status whole = write_session_file(p, s);
  ASSERT_FALSE(whole.ok());
  EXPECT_NE(whole.error().message().find("record 2: strength: value 0 is not a finite number"),
            std::string::npos)
      << whole.error().message();
  EXPECT_FALSE(fs::exists(p));
  {
    auto w = SessionWriter::create(p, s.header);
    ASSERT_TRUE(w.ok());
    ASSERT_TRUE(w->append(s.records[0]).ok());
    ASSERT_TRUE(w->append(s.records[1]).ok());
    EXPECT_FALSE(w->append(s.records[2]).ok());  // refused: the file stays readable
    ASSERT_TRUE(w->append(s.records[3]).ok());
  }
  const auto back = read_session_file(p);
  ASSERT_TRUE(back.ok()) << back.error().message();
  EXPECT_EQ(back->records.size(), 3u);
  fs::remove(p);
}

TEST(SessionFile, BundledSessionsReadIntactAndMatchTheirScripts) {
  for (std::string_view name : bundled_session_names()) {
    SessionReadInfo info;
    const auto s = read_session_file(bundled_session_path(name), &info);
    ASSERT_TRUE(s.ok()) << s.error().message();
    EXPECT_EQ(info.bytes_lost, 0) << name;
    EXPECT_GT(s->records.size(), 100u) << name;
    // The file in the tree is what the script writes today: regenerate it
    // (sculpt session generate NAME FILE) when a script changes on purpose.
    EXPECT_EQ(*s, bundled_session(name)) << name << " is out of date";
  }
}

}  // namespace
}  // namespace sculpt::sim
