// libFuzzer target: the probe file reader of `sculpt haptics trace`, and the
// trace reader. Seeds: corpus/probe_file.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "sculpt/core/haptics/probe_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace sculpt::core;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto probe = parse_probe_text(text, "fuzz.jsonl");
  if (probe.ok()) {
    // What the reader promises its users: time increasing from 0, bounded
    // coordinates, unit orientations.
    double last_t = -1.0;
    for (const ProbeSample& s : *probe) {
      if (!(s.t_s > last_t) || !(s.t_s >= 0.0)) __builtin_trap();
      last_t = s.t_s;
      for (int i = 0; i < 3; ++i)
        if (!(std::abs(s.at_vox[i]) <= kMaxProbeCoordinateVox)) __builtin_trap();
      if (s.orientation && !(std::abs(glm::length(*s.orientation) - 1.0f) < 1e-5f))
        __builtin_trap();
    }
  }
  const auto trace = parse_trace_text(text, "fuzz.jsonl");
  if (trace.ok()) {
    // Accepted trace lines write to text that reads back the same.
    std::string out;
    for (const TraceLine& l : *trace)
      out += format_trace_line(l);
    const auto back = parse_trace_text(out, "back.jsonl");
    if (!back.ok()) __builtin_trap();
    std::string again;
    for (const TraceLine& l : *back)
      again += format_trace_line(l);
    if (again != out) __builtin_trap();
  }
  return 0;
}
