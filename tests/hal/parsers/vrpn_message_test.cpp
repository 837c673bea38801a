// The VRPN message parser on good and bad bytes: the cookie, framing,
// descriptions and Pos_Quat, each as a real server would send them and as a
// broken or hostile one might.

#include "sculpt/hal/parsers/vrpn_message.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

namespace sculpt::hal {
namespace {

std::span<const uint8_t> as_bytes(std::string_view s) {
  return {reinterpret_cast<const uint8_t*>(s.data()), s.size()};
}

TEST(VrpnCookie, OursIsVersion07PaddedTo24BytesWithLogModeZero) {
  const auto c = make_vrpn_cookie();
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(c.data()), 19), "vrpn: ver. 07.38  0");
  for (size_t i = 19; i < kVrpnCookieBytes; ++i)
    EXPECT_EQ(c[i], 0) << "byte " << i;
  EXPECT_EQ(check_vrpn_cookie(c), VrpnCookieError::kNone);
}

TEST(VrpnCookie, AcceptsAnotherMinorVersionAndRefusesGarbage) {
  std::string other("vrpn: ver. 07.35  1\0\0\0\0\0", 24);
  EXPECT_EQ(check_vrpn_cookie(as_bytes(other)), VrpnCookieError::kNone);
  std::string major("vrpn: ver. 08.00  0\0\0\0\0\0", 24);
  EXPECT_EQ(check_vrpn_cookie(as_bytes(major)), VrpnCookieError::kMajorVersion);
  std::string http("HTTP/1.1 400 Bad Request\r\n");
  EXPECT_EQ(check_vrpn_cookie(as_bytes(http)), VrpnCookieError::kNotVrpn);
  std::string mode("vrpn: ver. 07.38  9\0\0\0\0\0", 24);
  EXPECT_EQ(check_vrpn_cookie(as_bytes(mode)), VrpnCookieError::kBadLogMode);
  const auto ours = make_vrpn_cookie();
  EXPECT_EQ(check_vrpn_cookie(std::span(ours).first(23)), VrpnCookieError::kShort);
}

TEST(VrpnFrame, HeaderIsFiveBigEndianInt32PaddedTo24AndPayloadTo8) {
  const std::vector<uint8_t> payload = {1, 2, 3, 4, 5};
  const auto bytes = encode_vrpn_message(7, 3, payload, 100, 200);
  ASSERT_EQ(bytes.size(), 24u + 8u);
  EXPECT_EQ(bytes[3], 24 + 5) << "length counts the header and the unpadded payload";
  EXPECT_EQ(bytes[15], 7);
  EXPECT_EQ(bytes[19], 3);
  VrpnMessage m;
  ASSERT_EQ(next_vrpn_message(bytes, m), VrpnFrameResult::kMessage);
  EXPECT_EQ(m.length, 29u);
  EXPECT_EQ(m.time_sec, 100);
  EXPECT_EQ(m.time_usec, 200);
  EXPECT_EQ(m.sender, 7);
  EXPECT_EQ(m.type, 3);
  EXPECT_EQ(std::vector<uint8_t>(m.payload.begin(), m.payload.end()), payload);
  EXPECT_EQ(m.consumed, 32u);
}

TEST(VrpnFrame, APartialMessageWaitsForMore) {
  const auto bytes = encode_vrpn_message(0, 0, encode_vrpn_pos_quat(0, {}, {0, 0, 0, 1}));
  VrpnMessage m;
  for (size_t n = 0; n < bytes.size(); ++n)
    EXPECT_EQ(next_vrpn_message(std::span(bytes).first(n), m), VrpnFrameResult::kNeedMore)
        << n << " bytes";
  EXPECT_EQ(next_vrpn_message(bytes, m), VrpnFrameResult::kMessage);
}

TEST(VrpnFrame, LengthsBelowTheHeaderOrAboveVrpnsBufferLoseTheStream) {
  auto bytes = encode_vrpn_message(0, 0, {});
  VrpnMessage m;
  bytes[3] = 23;
  EXPECT_EQ(next_vrpn_message(bytes, m), VrpnFrameResult::kBadLength);
  EXPECT_EQ(m.length, 23u);
  // 0xFFFFFFFF: judged from the first four bytes, without waiting for 4 GB.
  const std::vector<uint8_t> huge = {0xff, 0xff, 0xff, 0xff};
  EXPECT_EQ(next_vrpn_message(huge, m), VrpnFrameResult::kBadLength);
  const std::vector<uint8_t> just_over = {0x00, 0x00, 0xfa, 0x01};  // 64001
  EXPECT_EQ(next_vrpn_message(just_over, m), VrpnFrameResult::kBadLength);
}

TEST(VrpnDescription, NameWithItsNul) {
  const auto payload = encode_vrpn_description("Tracker0");
  ASSERT_EQ(payload.size(), 4u + 9u);
  EXPECT_EQ(payload[3], 9);
  std::string_view name;
  ASSERT_EQ(decode_vrpn_description(payload, name), VrpnPayloadError::kNone);
  EXPECT_EQ(name, "Tracker0");
}

TEST(VrpnDescription, BadNamesAreRefused) {
  std::string_view name;
  auto payload = encode_vrpn_description("Tracker0");
  payload.back() = 'x';  // no NUL at the end
  EXPECT_EQ(decode_vrpn_description(payload, name), VrpnPayloadError::kBadName);
  payload = encode_vrpn_description("Trac");
  payload[6] = 0;  // NUL inside
  EXPECT_EQ(decode_vrpn_description(payload, name), VrpnPayloadError::kBadName);
  payload = encode_vrpn_description("Tracker0");
  payload[3] = 200;  // longer than vrpn_CNAME
  EXPECT_EQ(decode_vrpn_description(payload, name), VrpnPayloadError::kBadName);
  payload[3] = 20;  // longer than the payload
  EXPECT_EQ(decode_vrpn_description(payload, name), VrpnPayloadError::kShort);
  payload = encode_vrpn_description("Tracker0");
  payload.push_back(0);
  EXPECT_EQ(decode_vrpn_description(payload, name), VrpnPayloadError::kLong);
  EXPECT_EQ(decode_vrpn_description(std::span(payload).first(3), name), VrpnPayloadError::kShort);
}

TEST(VrpnPosQuat, PositionInMillimetresQuaternionReorderedToWxyz) {
  const double h = std::sqrt(0.5);
  const auto payload = encode_vrpn_pos_quat(3, {0.1, -0.25, 1.5}, {0, h, 0, h});
  EXPECT_EQ(payload[3], 3);
  EXPECT_EQ(payload[7], 3) << "VRPN repeats the sensor as alignment filler";
  TrackerPose p;
  ASSERT_EQ(decode_vrpn_pos_quat(payload, p), VrpnPayloadError::kNone);
  EXPECT_EQ(p.sensor, 3);
  EXPECT_DOUBLE_EQ(p.position_mm[0], 100.0);
  EXPECT_DOUBLE_EQ(p.position_mm[1], -250.0);
  EXPECT_DOUBLE_EQ(p.position_mm[2], 1500.0);
  EXPECT_NEAR(p.quat_wxyz[0], h, 1e-15);
  EXPECT_NEAR(p.quat_wxyz[1], 0, 1e-15);
  EXPECT_NEAR(p.quat_wxyz[2], h, 1e-15);
  EXPECT_NEAR(p.quat_wxyz[3], 0, 1e-15);
}

TEST(VrpnPosQuat, BigEndianOnTheWire) {
  const auto payload = encode_vrpn_pos_quat(0, {1.0, 0, 0}, {0, 0, 0, 1});
  EXPECT_EQ(payload[8], 0x3F);  // 1.0 = 3FF0 0000 0000 0000, high byte first
  EXPECT_EQ(payload[9], 0xF0);
  EXPECT_EQ(payload[56], 0x3F);  // w = 1.0, last
}

TEST(VrpnPosQuat, ANonUnitQuaternionIsNormalised) {
  TrackerPose p;
  ASSERT_EQ(decode_vrpn_pos_quat(encode_vrpn_pos_quat(0, {}, {0, 0, 0, 2}), p),
            VrpnPayloadError::kNone);
  EXPECT_DOUBLE_EQ(p.quat_wxyz[0], 1.0);
  const double big = 1e200;  // would overflow if squared unscaled
  ASSERT_EQ(decode_vrpn_pos_quat(encode_vrpn_pos_quat(0, {}, {big, 0, 0, big}), p),
            VrpnPayloadError::kNone);
  EXPECT_NEAR(p.quat_wxyz[0], std::sqrt(0.5), 1e-15);
}

TEST(VrpnPosQuat, BadPayloadsAreRefusedAndLeaveThePoseAlone) {
  TrackerPose p;
  p.sensor = 42;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto good = encode_vrpn_pos_quat(0, {}, {0, 0, 0, 1});
  EXPECT_EQ(decode_vrpn_pos_quat(std::span(good).first(63), p), VrpnPayloadError::kShort);
  std::vector<uint8_t> longer(good.begin(), good.end());
  longer.push_back(0);
  EXPECT_EQ(decode_vrpn_pos_quat(longer, p), VrpnPayloadError::kLong);
  EXPECT_EQ(decode_vrpn_pos_quat(encode_vrpn_pos_quat(-1, {}, {0, 0, 0, 1}), p),
            VrpnPayloadError::kBadSensor);
  EXPECT_EQ(decode_vrpn_pos_quat(encode_vrpn_pos_quat(0, {nan, 0, 0}, {0, 0, 0, 1}), p),
            VrpnPayloadError::kNotFinite);
  EXPECT_EQ(decode_vrpn_pos_quat(encode_vrpn_pos_quat(0, {}, {0, 0, 0, nan}), p),
            VrpnPayloadError::kNotFinite);
  EXPECT_EQ(decode_vrpn_pos_quat(encode_vrpn_pos_quat(0, {1e307, 0, 0}, {0, 0, 0, 1}), p),
            VrpnPayloadError::kNotFinite)
      << "finite in metres, infinite in mm";
  EXPECT_EQ(decode_vrpn_pos_quat(encode_vrpn_pos_quat(0, {}, {0, 0, 0, 0}), p),
            VrpnPayloadError::kNotRotation);
  EXPECT_EQ(p.sensor, 42);
  EXPECT_EQ(describe(VrpnPayloadError::kNotRotation), "quaternion of zero length");
}

}  // namespace
}  // namespace sculpt::hal
