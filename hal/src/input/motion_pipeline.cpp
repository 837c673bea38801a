#include "sculpt/hal/input/motion_pipeline.h"

namespace sculpt::hal {

MotionPipeline::MotionPipeline(std::unique_ptr<ReportParser> parser, NormalizerConfig config)
    : parser_(std::move(parser)), normalizer_(config) {}

void MotionPipeline::feed(const RawEvent& event, uint32_t device_id, std::vector<InputEvent>& out) {
  const size_t first = out.size();
  parser_->parse(event, out);
  for (size_t i = first; i < out.size(); ++i) {
    out[i].device_id = device_id;
    normalizer_.apply(out[i]);
    integral_.accumulate(out[i]);
  }
}

}  // namespace sculpt::hal
