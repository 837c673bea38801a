#include "sculpt/sim/session/session_text.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include "sculpt/sim/session/session_file.h"
#include "sculpt/sim/synth/bundled_sessions.h"

namespace sculpt::sim {
namespace {

TEST(SessionText, ConvertsBothWaysWithoutLoss) {
  for (std::string_view name : bundled_session_names()) {
    const Session s = bundled_session(name);
    const std::string text = session_to_text(s);
    const auto back = session_from_text(text, "t.jsonl");
    ASSERT_TRUE(back.ok()) << back.error().message();
    EXPECT_EQ(*back, s);
    EXPECT_EQ(serialize_session(*back), serialize_session(s));  // byte for byte
    EXPECT_EQ(session_to_text(*back), text);
  }
}

TEST(SessionText, DeviceStringsThatAreNotUtf8SurviveTheRoundTrip) {
  // A device may report its name in Latin-1 or send garbage; JSON strings
  // hold only Unicode, so such a string is written as {"bytes": hex}.
  Session s = bundled_session("short");
  s.header.device.name = "Caf\xe9 Mouse";                     // Latin-1
  s.header.device.serial = std::string("\xff\x00\x80", 3);    // not text at all
  s.header.device.manufacturer = "3Dconnexion \xe2\x84\xa2";  // valid UTF-8 (TM)
  s.header.device.path = "\xed\xa0\x80";                      // an encoded surrogate
  const std::string text = session_to_text(s);
  EXPECT_NE(text.find("\"name\":{\"bytes\":\"43 61 66 e9 20 4d 6f 75 73 65\"}"), std::string::npos)
      << text.substr(0, 400);
  EXPECT_NE(text.find("\"manufacturer\":\"3Dconnexion \xe2\x84\xa2\""), std::string::npos);
  const auto back = session_from_text(text, "latin1.jsonl");
  ASSERT_TRUE(back.ok()) << back.error().message();
  EXPECT_EQ(back->header.device.name, s.header.device.name);
  EXPECT_EQ(back->header.device.serial, s.header.device.serial);
  EXPECT_EQ(back->header.device.manufacturer, s.header.device.manufacturer);
  EXPECT_EQ(back->header.device.path, s.header.device.path);
  EXPECT_EQ(serialize_session(*back), serialize_session(s));
}

TEST(SessionText, AHeaderNumberOutOfRangeIsRefusedBeforeAnyConversion) {
  // Found by fuzzing: a usage page of 1.8e124 was converted to a uint16_t.
  const std::string header_start =
      "{\"sculpt_session\": 1, \"device\": {\"backend\": \"sim\", \"vendor_product\": "
      "\"046d:c626\", ";
  for (const std::string field :
       {"\"usage_page\": 1.8e124", "\"usage_page\": 70000", "\"usage\": -1", "\"usage\": 8.5"}) {
    const auto r = session_from_text(header_start + field + "}}\n", "h.jsonl");
    ASSERT_FALSE(r.ok()) << field;
    EXPECT_NE(r.error().message().find("h.jsonl:1: usage"), std::string::npos)
        << r.error().message();
    EXPECT_NE(r.error().message().find("expected an integer from 0 to 65535"), std::string::npos)
        << r.error().message();
  }
  const auto time =
      session_from_text(header_start + "\"usage\": 8}, \"created_unix_ns\": 1e300}\n", "h.jsonl");
  ASSERT_FALSE(time.ok());
  EXPECT_NE(time.error().message().find("created_unix_ns"), std::string::npos);
}

// Found by fuzzing: a 400-byte backend name was read from text, but a
// session file holds 256, so the text did not convert to a file and back.
TEST(SessionText, AHeaderFieldLongerThanASessionFileHoldsIsRefused) {
  std::ifstream in(SCULPT_TEST_DATA_DIR "/session/fuzz_long_backend.jsonl", std::ios::binary);
  const std::string found((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(found.empty());
  const auto r = session_from_text(found, "f.jsonl");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message().find("f.jsonl:1: backend:"), std::string::npos)
      << r.error().message();
  EXPECT_NE(r.error().message().find("more than the 256 a session holds"), std::string::npos)
      << r.error().message();
  const std::string head =
      "{\"sculpt_session\": 1, \"device\": {\"vendor_product\": \"046d:c626\", ";
  const std::string fields[] = {
      "\"name\": \"" + std::string(kMaxDeviceTextBytes + 1, 'n') + "\"",
      "\"report_descriptor\": \"" + std::string(2 * (kMaxDescriptorBytes + 1), 'a') + "\""};
  for (const std::string& field : fields) {
    const auto long_field = session_from_text(head + field + "}}\n", "h.jsonl");
    ASSERT_FALSE(long_field.ok());
    EXPECT_NE(long_field.error().message().find("a session holds"), std::string::npos)
        << long_field.error().message();
  }
  // At the limit it is read, and converts to a file and back.
  const auto at_limit = session_from_text(
      head + "\"backend\": \"" + std::string(kMaxBackendBytes, 'b') + "\"}}\n", "h.jsonl");
  ASSERT_TRUE(at_limit.ok()) << at_limit.error().message();
  const auto back = parse_session_bytes(serialize_session(*at_limit), "b.scs");
  ASSERT_TRUE(back.ok()) << back.error().message();
  EXPECT_EQ(*back, *at_limit);
}

TEST(SessionText, ReadsAHandWrittenSessionWithPastedHex) {
  const std::string text =
      "# captured with usbhid-dump, pasted as is\n"
      R"({"sculpt_session": 1, "device": {"vendor_product": "046d:c626", "name": "SpaceNavigator"}})"
      "\n\n"
      R"({"t": 100, "report": "01 0A 00 F6 FF 00 00"})"
      "\n"
      R"({"t": 108, "report": "02:00:00:05:00:00:00"})"
      "\n"
      R"({"t": 110, "cmd": "mirror", "axis": "y", "at": 31.5})"
      "\n"
      R"({"t": 120, "cmd": "tool_pose", "position": [1, 2, 3], "orientation": [1, 0, 0, 0]})"
      "\n";
  const auto s = session_from_text(text, "hand.jsonl");
  ASSERT_TRUE(s.ok()) << s.error().message();
  EXPECT_EQ(s->header.device.vendor_id, 0x046d);
  ASSERT_EQ(s->records.size(), 4u);
  EXPECT_EQ(s->records[0].event.size, 7);
  EXPECT_EQ(s->records[0].event.data[3], 0xf6);
  EXPECT_EQ(s->records[1].event.data[3], 0x05);
  EXPECT_EQ(s->records[2].command.kind, CommandKind::kMirror);
  EXPECT_EQ(s->records[2].command.choice, 1);
  EXPECT_EQ(s->records[2].command.values[0], 31.5f);
}

TEST(SessionText, AnEmptyReportIsTrackingLostInTextAndBinaryAlike) {
  const std::string text =
      R"({"sculpt_session": 1, "device": {"backend": "opentrack", "path": "127.0.0.1:4242", "vendor_product": "0000:0000"}})"
      "\n"
      R"({"t": 100, "report": ""})"
      "\n";
  const auto s = session_from_text(text, "lost.jsonl");
  ASSERT_TRUE(s.ok()) << s.error().message();
  ASSERT_EQ(s->records.size(), 1u);
  EXPECT_EQ(s->records[0].event.kind, hal::RawEventKind::kReport);
  EXPECT_EQ(s->records[0].event.size, 0);
  const auto binary = parse_session_bytes(serialize_session(*s), "lost.scs");
  ASSERT_TRUE(binary.ok()) << binary.error().message();
  EXPECT_EQ(*binary, *s);
  const auto back = session_from_text(session_to_text(*binary), "lost.jsonl");
  ASSERT_TRUE(back.ok()) << back.error().message();
  EXPECT_EQ(*back, *s);
}

TEST(SessionText, TouchModeRoundTripsAndABadOneIsRefused) {
  const std::string text = R"({"sculpt_session": 1, "device": {"vendor_product": "046d:c626"}})"
                           "\n"
                           R"({"t": 1, "cmd": "touch", "on": true})"
                           "\n"
                           R"({"t": 2, "cmd": "touch", "on": false})"
                           "\n";
  const auto s = session_from_text(text, "touch.jsonl");
  ASSERT_TRUE(s.ok()) << s.error().message();
  ASSERT_EQ(s->records.size(), 2u);
  EXPECT_EQ(s->records[0].command.kind, CommandKind::kTouch);
  EXPECT_EQ(s->records[0].command.choice, 1);
  EXPECT_EQ(s->records[1].command.choice, 0);
  const auto again = session_from_text(session_to_text(*s), "again");
  ASSERT_TRUE(again.ok()) << again.error().message();
  EXPECT_EQ(*again, *s);
  const auto bad =
      session_from_text(R"({"sculpt_session": 1, "device": {"vendor_product": "046d:c626"}})"
                        "\n"
                        R"({"t": 1, "cmd": "touch", "on": 3})"
                        "\n",
                        "bad.jsonl");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message().find("on: expected true or false"), std::string::npos)
      << bad.error().message();
}

TEST(SessionText, ClutchAndTrackerCalibrationRoundTripAndBadOnesAreRefused) {
  const std::string head = R"({"sculpt_session": 1, "device": {"vendor_product": "0000:0000"}})"
                           "\n";
  const std::string text = head + R"({"t": 1, "cmd": "clutch", "held": true})"
                                  "\n"
                                  R"({"t": 2, "cmd": "clutch", "held": false})"
                                  "\n"
                                  R"({"t": 3, "cmd": "tracker", "scale_vox_per_mm": 0.5, )"
                                  R"("rotation": [0.5, 0.5, 0.5, 0.5]})"
                                  "\n"
                                  R"({"t": 4, "cmd": "hardness", "value": 0.25})"
                                  "\n";
  const auto s = session_from_text(text, "tracker.jsonl");
  ASSERT_TRUE(s.ok()) << s.error().message();
  ASSERT_EQ(s->records.size(), 4u);
  EXPECT_EQ(s->records[3].command.kind, CommandKind::kHardness);
  EXPECT_EQ(s->records[3].command.values[0], 0.25f);
  EXPECT_EQ(s->records[0].command.kind, CommandKind::kClutch);
  EXPECT_EQ(s->records[0].command.choice, 1);
  EXPECT_EQ(s->records[1].command.choice, 0);
  EXPECT_EQ(s->records[2].command.kind, CommandKind::kTracker);
  EXPECT_EQ(s->records[2].command.values[0], 0.5f);
  EXPECT_EQ(s->records[2].command.values[4], 0.5f);
  const auto again = session_from_text(session_to_text(*s), "again");
  ASSERT_TRUE(again.ok()) << again.error().message();
  EXPECT_EQ(*again, *s);
  const std::vector<uint8_t> bytes = serialize_session(*s);
  const auto binary = parse_session_bytes(bytes, "tracker.scs");
  ASSERT_TRUE(binary.ok()) << binary.error().message();
  EXPECT_EQ(*binary, *s);
  const struct {
    const char* line;
    const char* says;
  } bad[] = {
      {R"({"t": 1, "cmd": "clutch", "held": 1})", "held: expected true or false"},
      {R"({"t": 1, "cmd": "clutch"})", "missing \"held\""},
      {R"({"t": 1, "cmd": "tracker", "scale_vox_per_mm": -1, "rotation": [1, 0, 0, 0]})",
       "tracker scale -1 is outside"},
      {R"({"t": 1, "cmd": "tracker", "scale_vox_per_mm": 1, "rotation": [1, 1, 0, 0]})",
       "not a unit quaternion"},
      {R"({"t": 1, "cmd": "tracker", "scale_vox_per_mm": 1, "rotation": [1, 0, 0]})",
       "rotation: expected 4 numbers"},
  };
  for (const auto& [line, says] : bad) {
    const auto r = session_from_text(head + line + "\n", "bad.jsonl");
    ASSERT_FALSE(r.ok()) << line;
    EXPECT_NE(r.error().message().find(says), std::string::npos) << r.error().message();
    EXPECT_NE(r.error().message().find("bad.jsonl"), std::string::npos) << r.error().message();
  }
}

TEST(SessionText, SheetCommandsRoundTripThroughTextAndBinary) {
  const std::string text =
      R"({"sculpt_session": 1, "device": {"vendor_product": "046d:c626"}})"
      "\n"
      R"({"t": 1, "cmd": "sheet", "action": "place", "centre": [32, 40, 30], "size": 30, "points": 8, "axis": "y"})"
      "\n"
      R"({"t": 2, "cmd": "sheet", "action": "edit", "on": true, "influence": "zone", "radius": 0.25})"
      "\n"
      R"({"t": 3, "cmd": "sheet", "action": "subtract", "thickness": 2.5})"
      "\n"
      R"({"t": 4, "cmd": "sheet", "action": "remove"})"
      "\n";
  const auto s = session_from_text(text, "sheet.jsonl");
  ASSERT_TRUE(s.ok()) << s.error().message();
  ASSERT_EQ(s->records.size(), 4u);
  const Command& place = s->records[0].command;
  EXPECT_EQ(place.kind, CommandKind::kSheet);
  EXPECT_EQ(place.choice, static_cast<uint8_t>(SheetAction::kPlace));
  EXPECT_EQ(place.values[1], 40.0f);
  EXPECT_EQ(place.values[5], 1.0f);  // y
  const Command& edit = s->records[1].command;
  EXPECT_EQ(edit.choice, static_cast<uint8_t>(SheetAction::kEdit));
  EXPECT_EQ(edit.values[0], 1.0f);
  EXPECT_EQ(edit.values[1], 2.0f);  // zone
  EXPECT_EQ(edit.values[2], 0.25f);
  EXPECT_EQ(s->records[2].command.values[0], 2.5f);
  const auto again = session_from_text(session_to_text(*s), "again.jsonl");
  ASSERT_TRUE(again.ok()) << again.error().message();
  EXPECT_EQ(*again, *s);
  const auto binary = parse_session_bytes(serialize_session(*s), "sheet.scs");
  ASSERT_TRUE(binary.ok()) << binary.error().message();
  EXPECT_EQ(*binary, *s);
}

TEST(SessionText, HapticRecordsRoundTripThroughTextAndBinaryAndBadOnesAreRefused) {
  const std::string header = R"({"sculpt_session": 1, "device": {"vendor_product": "046d:c626"}})"
                             "\n";
  const std::string text =
      header +
      R"({"t": 1, "haptic": "start", "settings": "proxy.radius_vox = 3\nvoxel_mm = 0.5\n"})"
      "\n"
      R"({"t": 2, "haptic": "patch", "version": 1, "centre": [32, 51.25, 32]})"
      "\n"
      R"({"t": 3, "haptic": "tick", "tick_t": 2500000, "index": 0, "buttons": 1, "flags": 9, "inputs": 3, "position_mm": [0, -0.125, 1e-7], "force_n": [0, 2.5, -0.1]})"
      "\n";
  const auto s = session_from_text(text, "haptic.jsonl");
  ASSERT_TRUE(s.ok()) << s.error().message();
  ASSERT_EQ(s->records.size(), 3u);
  const HapticRecord& tick = s->records[2].haptic;
  EXPECT_EQ(s->records[2].kind, SessionRecord::Kind::kHaptic);
  EXPECT_EQ(tick.type, HapticRecord::Type::kTick);
  EXPECT_EQ(tick.tick_t_ns, 2'500'000);
  EXPECT_EQ(tick.flags, kTickHomed | 1 << kTickRequestShift);
  EXPECT_EQ(tick.values[2], 1e-7f);
  EXPECT_EQ(tick.values[5], -0.1f);
  EXPECT_EQ(s->records[1].haptic.tag, 1u);
  const auto again = session_from_text(session_to_text(*s), "again.jsonl");
  ASSERT_TRUE(again.ok()) << again.error().message();
  EXPECT_EQ(*again, *s);
  const auto binary = parse_session_bytes(serialize_session(*s), "haptic.scs");
  ASSERT_TRUE(binary.ok()) << binary.error().message();
  EXPECT_EQ(*binary, *s);

  auto error = [&](const std::string& body) {
    const auto r = session_from_text(header + body, "bad.jsonl");
    return r.ok() ? std::string("accepted") : r.error().message();
  };
  EXPECT_EQ(error(R"({"t": 1, "haptic": "wobble"})"),
            "bad.jsonl:2: haptic: unknown record \"wobble\"");
  EXPECT_EQ(error(R"({"t": 1, "haptic": "start", "settings": "Stiffness = 1"})"),
            "bad.jsonl:2: haptic start: set-up text: line 1: a name holds only a-z, 0-9, _ and .");
  EXPECT_EQ(error(R"({"t": 1, "haptic": "start", "settings": "a = nan"})"),
            "bad.jsonl:2: haptic start: set-up text: line 1: a: not a finite number");
  EXPECT_EQ(
      error(
          R"({"t": 1, "haptic": "tick", "tick_t": 1, "index": 0, "buttons": 0, "flags": 22, "inputs": 0, "position_mm": [0, 0, 0], "force_n": [0, 0, 0]})"),
      "bad.jsonl:2: haptic tick: unknown tick flags");
  EXPECT_EQ(error(R"({"t": 1, "haptic": "patch", "version": -1, "centre": [0, 0, 0]})"),
            "bad.jsonl:2: version: expected an integer 0..18446744073709551615");
  // The binary reader refuses the same: a tick whose force is not finite.
  Session bad = *s;
  bad.records[2].haptic.values[4] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(write_session_file(testing::TempDir() + "/never.scs", bad).ok());
  std::vector<uint8_t> bytes = serialize_session(*s);
  bad.records.resize(2);
  const size_t kept = serialize_session(bad).size();
  SessionReadInfo info;
  // The tick's position x (after i64, u32, u32, u8, u64) becomes NaN, and
  // the record's CRC is made right again: the checksum holds, the value not.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&bytes[kept + 12 + 25], &nan, sizeof nan);
  const uint32_t crc = static_cast<uint32_t>(crc32(0, &bytes[kept], 12 + 49));
  std::memcpy(&bytes[kept + 12 + 49], &crc, sizeof crc);
  const auto cut = parse_session_bytes(bytes, "cut.scs", &info);
  ASSERT_TRUE(cut.ok());
  EXPECT_EQ(cut->records.size(), 2u);
  EXPECT_EQ(info.bytes_lost, 12 + 49 + 4);
  EXPECT_NE(info.warning.find("haptic tick record: value out of range"), std::string::npos)
      << info.warning;
}

TEST(SessionText, ErrorsNameTheLineAndTheProblem) {
  const std::string header = R"({"sculpt_session": 1, "device": {"vendor_product": "046d:c626"}})"
                             "\n";
  auto error = [&](const std::string& body) {
    const auto r = session_from_text(header + body, "bad.jsonl");
    return r.ok() ? std::string("accepted") : r.error().message();
  };
  EXPECT_EQ(error(R"({"t": 1, "report": "zz"})"), "bad.jsonl:2: report: 'zz' is not hex");
  EXPECT_EQ(error(R"({"t": 1, "report": "0"})"), "bad.jsonl:2: report: '0' is not hex");
  EXPECT_EQ(error("{\"t\": 5, \"sync\": true}\n{\"t\": 4, \"sync\": true}"),
            "bad.jsonl:3: t goes back in time");
  EXPECT_EQ(error(R"({"t": 1, "cmd": "explode"})"),
            "bad.jsonl:2: cmd: unknown command \"explode\"");
  EXPECT_EQ(error(R"({"t": 1, "cmd": "tool", "shape": "blob", "size": [1, 2]})"),
            "bad.jsonl:2: shape: unknown value \"blob\"");
  EXPECT_EQ(error(R"({"t": 1, "cmd": "tool", "shape": "cube", "size": [1]})"),
            "bad.jsonl:2: size: expected 2 numbers");
  EXPECT_EQ(error(R"({"t": 1, "cmd": "sheet", "action": "fold"})"),
            "bad.jsonl:2: action: unknown value \"fold\"");
  EXPECT_EQ(
      error(
          R"({"t": 1, "cmd": "sheet", "action": "place", "centre": [1, 2, 3], "size": 9, "points": 8, "axis": "w"})"),
      "bad.jsonl:2: axis: expected x, y or z");
  EXPECT_EQ(
      error(
          R"({"t": 1, "cmd": "sheet", "action": "edit", "on": 1, "influence": "zone", "radius": 1})"),
      "bad.jsonl:2: on: expected true or false");
  EXPECT_EQ(error("not json"), "bad.jsonl:2: not a JSON object");
  EXPECT_EQ(error(R"({"report": "01"})"), "bad.jsonl:2: missing \"t\"");
  EXPECT_EQ(error(R"({"t": 1, "report": ")" + std::string(65 * 2, 'a') + "\"}"),
            "bad.jsonl:2: report: expected 0 to 64 bytes");
  const auto no_header = session_from_text(R"({"t": 1, "sync": true})", "h.jsonl");
  ASSERT_FALSE(no_header.ok());
  EXPECT_NE(no_header.error().message().find("h.jsonl:1: the first line must be the header"),
            std::string::npos);
  EXPECT_FALSE(session_from_text("", "e.jsonl").ok());
}

}  // namespace
}  // namespace sculpt::sim
