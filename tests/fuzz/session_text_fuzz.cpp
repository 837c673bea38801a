// libFuzzer target: the JSON Lines session reader. Seeds: corpus/session_text.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "sculpt/sim/session/session_file.h"
#include "sculpt/sim/session/session_text.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto session = sculpt::sim::session_from_text(text, "fuzz.jsonl");
  if (session.ok()) {
    // Accepted text converts to binary and back without loss.
    auto back = sculpt::sim::parse_session_bytes(sculpt::sim::serialize_session(*session), "b.scs");
    if (!back.ok() || !(*back == *session)) __builtin_trap();
  }
  return 0;
}
