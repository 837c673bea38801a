// libFuzzer target: a device's report descriptor and the reports it then
// sends, as a hostile or broken device would (hidraw hands both over
// unchecked). Input: one byte n, n bytes of descriptor (n < 256), then
// reports of up to 64 bytes, each preceded by its length byte. Seeds:
// corpus/hid_report. The layout must stay bounded whatever it declares.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "sculpt/hal/parsers/hid_descriptor.h"
#include "sculpt/hal/parsers/hid_descriptor_parser.h"
#include "sculpt/hal/types/raw_event.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace sculpt::hal;
  if (size == 0) return 0;
  const size_t n = std::min<size_t>(data[0], size - 1);
  auto layout = parse_hid_descriptor(std::span(data + 1, n));
  if (!layout.ok()) return 0;
  if (layout->buttons.size() > 1024) __builtin_trap();
  HidDescriptorParser parser(std::move(layout).value());
  std::vector<InputEvent> out;
  int64_t t = 0;
  for (size_t at = 1 + n; at < size;) {
    const size_t length = std::min<size_t>({data[at], RawEvent::kMaxReportBytes, size - at - 1});
    parser.parse(RawEvent::report(t += 1000, std::span(data + at + 1, length)), out);
    at += 1 + length;
  }
  return 0;
}
