// The OpenTrack datagram decoder on good and bad bytes: a tracker's pose must
// arrive in mm and as the right rotation, and nothing malformed may pass.

#include "sculpt/hal/parsers/opentrack_datagram.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace sculpt::hal {
namespace {

constexpr double kEps = 1e-12;

TEST(OpenTrackDatagram, PositionInMillimetresFromCentimetres) {
  const auto bytes = encode_opentrack_datagram(1.5, -2.0, 30.25, 0, 0, 0);
  TrackerPose pose;
  ASSERT_EQ(decode_opentrack_datagram(bytes, pose), OpenTrackDatagramError::kNone);
  EXPECT_EQ(pose.sensor, 0);
  EXPECT_DOUBLE_EQ(pose.position_mm[0], 15.0);
  EXPECT_DOUBLE_EQ(pose.position_mm[1], -20.0);
  EXPECT_DOUBLE_EQ(pose.position_mm[2], 302.5);
  EXPECT_DOUBLE_EQ(pose.quat_wxyz[0], 1.0);
}

TEST(OpenTrackDatagram, BytesAreLittleEndianFloat64InOpenTrackOrder) {
  // x = 1.0 cm is 0x3FF0000000000000, written low byte first.
  const auto bytes = encode_opentrack_datagram(1.0, 0, 0, 0, 0, 0);
  EXPECT_EQ(bytes[6], 0xF0);
  EXPECT_EQ(bytes[7], 0x3F);
  for (int i = 8; i < 48; ++i)
    EXPECT_EQ(bytes[i], 0) << "byte " << i;
}

TEST(OpenTrackDatagram, YawTurnsAboutUpPitchAboutRightRollAboutTowardUser) {
  TrackerPose pose;
  ASSERT_EQ(decode_opentrack_datagram(encode_opentrack_datagram(0, 0, 0, 90, 0, 0), pose),
            OpenTrackDatagramError::kNone);
  const double h = std::sqrt(0.5);
  EXPECT_NEAR(pose.quat_wxyz[0], h, kEps);
  EXPECT_NEAR(pose.quat_wxyz[2], h, kEps);  // about +Y
  ASSERT_EQ(decode_opentrack_datagram(encode_opentrack_datagram(0, 0, 0, 0, 90, 0), pose),
            OpenTrackDatagramError::kNone);
  EXPECT_NEAR(pose.quat_wxyz[1], h, kEps);  // about +X
  ASSERT_EQ(decode_opentrack_datagram(encode_opentrack_datagram(0, 0, 0, 0, 0, 90), pose),
            OpenTrackDatagramError::kNone);
  EXPECT_NEAR(pose.quat_wxyz[3], h, kEps);  // about +Z
}

TEST(OpenTrackDatagram, YawIsAppliedBeforePitchAndRoll) {
  // Ry(yaw) * Rx(pitch) * Rz(roll), checked against the product written out.
  const auto q = quat_from_yaw_pitch_roll_deg(30, 20, 10);
  const auto mul = [](std::array<double, 4> a, std::array<double, 4> b) {
    return std::array<double, 4>{a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
                                 a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
                                 a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
                                 a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
  };
  const double r = 3.14159265358979323846 / 360.0;
  const std::array<double, 4> qy{std::cos(30 * r), 0, std::sin(30 * r), 0};
  const std::array<double, 4> qx{std::cos(20 * r), std::sin(20 * r), 0, 0};
  const std::array<double, 4> qz{std::cos(10 * r), 0, 0, std::sin(10 * r)};
  const auto want = mul(mul(qy, qx), qz);
  double norm = 0;
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(q[i], want[i], kEps) << "component " << i;
    norm += q[i] * q[i];
  }
  EXPECT_NEAR(norm, 1.0, kEps);
}

TEST(OpenTrackDatagram, ShortAndLongDatagramsAreRefused) {
  const auto good = encode_opentrack_datagram(1, 2, 3, 4, 5, 6);
  TrackerPose pose;
  pose.position_mm = {7, 7, 7};
  EXPECT_EQ(decode_opentrack_datagram({}, pose), OpenTrackDatagramError::kShort);
  EXPECT_EQ(decode_opentrack_datagram(std::span(good.data(), 47), pose),
            OpenTrackDatagramError::kShort);
  std::vector<uint8_t> longer(good.begin(), good.end());
  longer.push_back(0);
  EXPECT_EQ(decode_opentrack_datagram(longer, pose), OpenTrackDatagramError::kLong);
  EXPECT_EQ(pose.position_mm[0], 7) << "a refused datagram must leave the pose alone";
}

TEST(OpenTrackDatagram, NaNInfinityAndOverflowAreRefused) {
  TrackerPose pose;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(decode_opentrack_datagram(encode_opentrack_datagram(nan, 0, 0, 0, 0, 0), pose),
            OpenTrackDatagramError::kNotFinite);
  EXPECT_EQ(decode_opentrack_datagram(encode_opentrack_datagram(0, 0, 0, 0, 0, -inf), pose),
            OpenTrackDatagramError::kNotFinite);
  // Finite in cm, infinite in mm.
  const double huge = std::numeric_limits<double>::max();
  EXPECT_EQ(decode_opentrack_datagram(encode_opentrack_datagram(0, huge, 0, 0, 0, 0), pose),
            OpenTrackDatagramError::kNotFinite);
  EXPECT_EQ(describe(OpenTrackDatagramError::kNotFinite), "NaN or infinity in the datagram");
}

}  // namespace
}  // namespace sculpt::hal
