#pragma once
// Parser + normaliser + deflection integral for one device, synchronous: RawEvent in, InputEvents
// out. The reader thread runs it live; a replay runs it directly on recorded
// events, so both produce the same samples for the same bytes.

#include <memory>
#include <vector>

#include "sculpt/hal/normalizer/normalizer.h"
#include "sculpt/hal/parsers/report_parser.h"
#include "sculpt/hal/pose/deflection_integral.h"

namespace sculpt::hal {

class MotionPipeline {
 public:
  MotionPipeline(std::unique_ptr<ReportParser> parser, NormalizerConfig config);
  /// Appends the normalised events `event` completes to `out` (device_id set).
  void feed(const RawEvent& event, uint32_t device_id, std::vector<InputEvent>& out);
  const ParserCounters& parser_counters() const { return parser_->counters(); }
  Normalizer& normalizer() { return normalizer_; }

 private:
  std::unique_ptr<ReportParser> parser_;
  Normalizer normalizer_;
  DeflectionIntegral integral_;
};

}  // namespace sculpt::hal
