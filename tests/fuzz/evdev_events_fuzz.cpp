// libFuzzer target: what a session holds for an evdev 6-axis device, the
// layout (its report descriptor) and the event records, through
// decode_evdev_layout() and EvdevEventParser as a replay runs them.
//
// Input: byte 0 = the layout's length L, then L bytes of layout (a layout
// that does not decode is replaced by six absolute +-350 axes and two
// buttons, so the records are still fuzzed); then chunks, each a length
// byte and that many bytes as one report (over 64: truncated, as
// RawEvent::report() cuts it). Checks: no crash; a decoded layout encodes
// back to the same bytes; motion axes finite and within [-1, 1]; buttons
// only the layout's; a second parser fed the same reports gives the same
// events (no hidden state). Seeds: corpus/evdev_events.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "sculpt/hal/parsers/evdev_event_parser.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace sculpt::hal;
  if (size == 0) return 0;
  size_t at = 1;
  const size_t layout_bytes = std::min<size_t>(data[0], size - 1);
  const std::span<const uint8_t> layout_span(data + at, layout_bytes);
  at += layout_bytes;
  EvdevLayout layout;
  if (decode_evdev_layout(layout_span, layout) == EvdevLayoutError::kNone) {
    const std::vector<uint8_t> again = encode_evdev_layout(layout);
    if (!std::equal(again.begin(), again.end(), layout_span.begin(), layout_span.end()))
      __builtin_trap();
  } else {
    layout = EvdevLayout{};
    layout.button_codes = {0x100, 0x101};
  }

  EvdevEventParser first(layout);
  EvdevEventParser second(layout);
  std::vector<InputEvent> a;
  std::vector<InputEvent> b;
  int64_t t = 0;
  while (at < size) {
    const size_t n = std::min<size_t>(data[at], size - at - 1);
    const RawEvent e = RawEvent::report(++t, std::span(data + at + 1, n));
    at += 1 + n;
    first.parse(e, a);
    second.parse(e, b);
  }
  if (a.size() != b.size()) __builtin_trap();
  for (size_t i = 0; i < a.size(); ++i) {
    const InputEvent& e = a[i];
    if (e.kind == InputKind::kMotion) {
      for (float v : e.axes) {
        if (!std::isfinite(v) || v < -1.0f || v > 1.0f) __builtin_trap();
      }
    } else if (e.kind == InputKind::kButton) {
      if (e.button < 0 || static_cast<size_t>(e.button) >= layout.button_codes.size())
        __builtin_trap();
    } else {
      __builtin_trap();  // the parser makes motion and buttons only
    }
    if (e.kind != b[i].kind || e.axes != b[i].axes || e.button != b[i].button ||
        e.pressed != b[i].pressed || e.t_ns != b[i].t_ns)
      __builtin_trap();
  }
  return 0;
}
