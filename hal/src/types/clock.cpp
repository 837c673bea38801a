#include "sculpt/hal/types/clock.h"

#include <time.h>

namespace sculpt::hal {

int64_t monotonic_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return int64_t{ts.tv_sec} * 1'000'000'000 + ts.tv_nsec;
}

}  // namespace sculpt::hal
