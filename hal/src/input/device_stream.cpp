#include "sculpt/hal/input/device_stream.h"

#include <utility>

namespace sculpt::hal {

namespace {

InputEvent lifecycle_event(InputKind kind, uint32_t device_id, int64_t t_ns) {
  InputEvent e;
  e.kind = kind;
  e.device_id = device_id;
  e.t_ns = t_ns;
  return e;
}

}  // namespace

DeviceStream::DeviceStream(uint32_t device_id, MotionPipeline first, PipelineFactory replug)
    : device_id_(device_id), pipeline_(std::move(first)), replug_(std::move(replug)) {}

void DeviceStream::connect(int64_t t_ns, std::vector<InputEvent>& out) {
  if (connected_) return;
  out.push_back(lifecycle_event(InputKind::kConnected, device_id_, t_ns));
  connected_ = true;
}

void DeviceStream::feed(const RawEvent& raw, std::vector<InputEvent>& out) {
  if (raw.kind == RawEventKind::kRemoved) {
    disconnect(raw.t_ns, out);
    if (replug_) {
      earlier_ += pipeline_.parser_counters();
      pipeline_ = replug_();
    }
    return;
  }
  connect(raw.t_ns, out);
  pipeline_.feed(raw, device_id_, out);
}

void DeviceStream::disconnect(int64_t t_ns, std::vector<InputEvent>& out) {
  out.push_back(lifecycle_event(InputKind::kDisconnected, device_id_, t_ns));
  connected_ = false;
}

ParserCounters DeviceStream::parser_counters() const {
  ParserCounters c = earlier_;
  c += pipeline_.parser_counters();
  return c;
}

}  // namespace sculpt::hal
