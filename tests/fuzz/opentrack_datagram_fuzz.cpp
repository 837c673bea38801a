// libFuzzer target: one UDP datagram as the OpenTrack receiver hands it to
// decode_opentrack_datagram(). Checks: no crash; a datagram is accepted only
// at exactly 48 bytes; an accepted pose is finite with a unit quaternion;
// decoding the same bytes twice gives the same pose (no hidden state).
// Seeds: corpus/opentrack_datagram.

#include <cstddef>
#include <cstdint>
#include <span>

#include "sculpt/hal/parsers/opentrack_datagram.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace sculpt::hal;
  const std::span<const uint8_t> bytes(data, size);
  TrackerPose pose;
  const OpenTrackDatagramError error = decode_opentrack_datagram(bytes, pose);
  if (describe(error).empty()) __builtin_trap();
  if (error != OpenTrackDatagramError::kNone) return 0;
  if (size != kOpenTrackDatagramBytes) __builtin_trap();
  if (!is_finite_unit_pose(pose)) __builtin_trap();
  TrackerPose again;
  if (decode_opentrack_datagram(bytes, again) != error || again.position_mm != pose.position_mm ||
      again.quat_wxyz != pose.quat_wxyz)
    __builtin_trap();
  return 0;
}
