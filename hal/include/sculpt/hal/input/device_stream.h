#pragma once
// A device's life as the station sees it: kConnected, its normalised events,
// kDisconnected. The one place that brackets a MotionPipeline with the
// device's coming and going, used by the live reader thread and by a replay,
// so both hand the station the same event sequence for the same raw events.
//
// A removal (RawEventKind::kRemoved) ends the device: kDisconnected carries
// the transport's time. A replayed session may go on after a removal (the
// device was plugged back in): the stream then starts a fresh pipeline, as
// the live registry opens a fresh reader, with no memory of held buttons.

#include <cstdint>
#include <functional>
#include <vector>

#include "sculpt/hal/input/motion_pipeline.h"
#include "sculpt/hal/types/input_event.h"
#include "sculpt/hal/types/raw_event.h"

namespace sculpt::hal {

class DeviceStream {
 public:
  /// Makes the pipeline for a re-plugged device; empty when the stream ends
  /// at its first removal (a live reader: the registry opens a new one).
  using PipelineFactory = std::function<MotionPipeline()>;

  DeviceStream(uint32_t device_id, MotionPipeline first, PipelineFactory replug = {});

  /// Appends kConnected at `t_ns` unless the device is connected already.
  void connect(int64_t t_ns, std::vector<InputEvent>& out);
  /// Appends what `raw` means: its events (after a kConnected when the
  /// device was not connected), or kDisconnected for a removal.
  void feed(const RawEvent& raw, std::vector<InputEvent>& out);
  /// Appends kDisconnected at `t_ns` (the device goes, or the reader stops).
  void disconnect(int64_t t_ns, std::vector<InputEvent>& out);

  bool connected() const { return connected_; }
  /// Reports the parsers could not use, over every pipeline this stream had.
  ParserCounters parser_counters() const;

 private:
  uint32_t device_id_;
  MotionPipeline pipeline_;
  PipelineFactory replug_;
  ParserCounters earlier_;  // of pipelines retired by a removal
  bool connected_ = false;
};

}  // namespace sculpt::hal
