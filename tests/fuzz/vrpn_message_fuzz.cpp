// libFuzzer target: a VRPN server's TCP stream as the tracker client sees
// it: a cookie, then messages framed one after another; every description
// and every user message's payload goes through its decoder, and the whole
// input also goes through the Pos_Quat decoder alone (the path a replayed
// session takes). Checks: no crash; framing never reads past the input and
// always advances by a multiple of 8; an accepted name is short and has no
// NUL; an accepted pose is finite with a unit quaternion.
// Seeds: corpus/vrpn_message.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "sculpt/hal/parsers/vrpn_message.h"

namespace {

void check_pose(std::span<const uint8_t> payload) {
  using namespace sculpt::hal;
  TrackerPose pose;
  if (decode_vrpn_pos_quat(payload, pose) != VrpnPayloadError::kNone) return;
  if (payload.size() != kVrpnPosQuatBytes || pose.sensor < 0) __builtin_trap();
  if (!is_finite_unit_pose(pose)) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace sculpt::hal;
  const std::span<const uint8_t> input(data, size);
  check_pose(input);
  if (check_vrpn_cookie(input) != VrpnCookieError::kNone) return 0;
  std::span<const uint8_t> stream = input.subspan(kVrpnCookieBytes);
  for (;;) {
    VrpnMessage m;
    const VrpnFrameResult r = next_vrpn_message(stream, m);
    if (r != VrpnFrameResult::kMessage) break;
    if (m.consumed < kVrpnHeaderBytes || m.consumed % 8 != 0 || m.consumed > stream.size() ||
        m.payload.size() != m.length - kVrpnHeaderBytes || m.payload.data() < stream.data() ||
        m.payload.data() + m.payload.size() > stream.data() + stream.size())
      __builtin_trap();
    if (m.type == kVrpnSenderDescription || m.type == kVrpnTypeDescription) {
      std::string_view name;
      if (decode_vrpn_description(m.payload, name) == VrpnPayloadError::kNone &&
          (name.size() >= kVrpnMaxNameBytes || name.find('\0') != std::string_view::npos))
        __builtin_trap();
    } else if (m.type >= 0) {
      check_pose(m.payload);
    }
    stream = stream.subspan(m.consumed);
  }
  return 0;
}
