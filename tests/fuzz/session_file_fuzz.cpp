// libFuzzer target: the binary session reader must refuse or truncate any
// input with one message, never crash, hang or allocate without bound.
// Seeds: sim/sessions/*.scs.

#include <cstddef>
#include <cstdint>
#include <span>

#include "sculpt/sim/session/session_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  sculpt::sim::SessionReadInfo info;
  auto session = sculpt::sim::parse_session_bytes(std::span(data, size), "fuzz.scs", &info);
  if (session.ok()) {
    // Whatever was accepted must write back and read again identically.
    const std::vector<uint8_t> again = sculpt::sim::serialize_session(*session);
    auto back = sculpt::sim::parse_session_bytes(again, "again.scs");
    if (!back.ok() || !(*back == *session)) __builtin_trap();
  }
  return 0;
}
