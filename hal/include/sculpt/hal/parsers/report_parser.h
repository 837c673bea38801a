#pragma once
// A family parser turns RawEvents into InputEvents. Parsers are independent
// of the transport (SDL's HIDAPI drivers): the same bytes give the same
// events whether they came from hidraw, libusb or a replayed session.

#include <cstdint>
#include <vector>

#include "sculpt/hal/types/input_event.h"
#include "sculpt/hal/types/raw_event.h"

namespace sculpt::hal {

/// What a parser could not use. Bad device input is counted, never thrown.
struct ParserCounters {
  int64_t reports = 0;          ///< RawEvents seen
  int64_t unknown_reports = 0;  ///< report ids this family does not define
  int64_t short_reports = 0;    ///< shorter than their layout: ignored
  /// Longer than their layout (or truncated): the layout part is used.
  int64_t overlong_reports = 0;
  /// Unusable as a whole (a tracker's NaN, its wrong length): dropped.
  int64_t invalid_reports = 0;

  ParserCounters& operator+=(const ParserCounters& other) {
    reports += other.reports;
    unknown_reports += other.unknown_reports;
    short_reports += other.short_reports;
    overlong_reports += other.overlong_reports;
    invalid_reports += other.invalid_reports;
    return *this;
  }
};

class ReportParser {
 public:
  virtual ~ReportParser() = default;
  /// Decodes one event and appends what it completes to `out` (often nothing:
  /// half of a split motion sample). kRemoved yields nothing: the reader
  /// turns it into kDisconnected.
  virtual void parse(const RawEvent& event, std::vector<InputEvent>& out) = 0;
  const ParserCounters& counters() const { return counters_; }

 protected:
  ParserCounters counters_;
};

}  // namespace sculpt::hal
